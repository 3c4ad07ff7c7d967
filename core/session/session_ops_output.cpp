// Actions that write files: session.save, export.*, and the contract's ops whose features have
// not landed yet (a clear error instead of a silent pass).
#include "core/session/session_ops.hpp"

namespace faultline::core::detail {

void registerOutputOps(OpTable& ops) {
    addAction(ops, "session.save", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"path"});
        const std::string path = s.outputPath(args::string(cmd, "path"));
        try {
            saveSessionFile(s.state(), path);
        } catch (const std::exception& e) {
            throw CommandError(std::string("session.save: ") + e.what());
        }
        return nullptr;
    });
    addNotYet(ops, "export.csv", "CSV export lands with the fault analysis");
    addNotYet(ops, "surface.build", "surfaces land with the implicit-surface feature");
    addNotYet(ops, "export.vdb", "VDB export lands with the implicit-surface feature");
    addNotYet(ops, "export.gltf", "glTF export lands with the implicit-surface feature");
    addNotYet(ops, "render", "rendering needs the renderer; run `faultline replay` from a build with the GUI");
}

} // namespace faultline::core::detail
