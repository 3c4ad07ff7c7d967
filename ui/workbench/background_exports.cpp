#include "ui/workbench/background_exports.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/session/atomic_file.hpp"
#include "core/session/commands.hpp"
#include "core/session/csv_exports.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/journal_place.hpp"
#include "core/session/session.hpp"
#include "ui/context/job_interrupter.hpp"
#include "ui/context/panel_context.hpp"

#include <filesystem>
#include <memory>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

void BackgroundExports::surfaces(std::vector<std::string> faults, const std::string& pathIn,
                                 bool vdb, bool glyphs) {
    const std::string path = absolutePath(pathIn);
    std::shared_ptr<const core::Frame> frame;
    try {
        frame = m_session.currentFrame();
    } catch (const std::exception& e) {
        return m_ctx.error(std::string("Cannot export: ") + e.what());
    }
    if (!frame || faults.empty())
        return m_ctx.error("Cannot export: no data or no fault");
    const core::SessionState& state = m_session.state();
    std::vector<core::FaultSurfaceRequest> requests;
    // The visible spheres of the current frame as the export.vdb / export.gltf ops take them
    // (not a view's: it may show a drag's preview), so a replay exports the same.
    const auto visibility = std::make_shared<const core::VisibilityResult>(m_session.visibility());
    for (const auto& name : faults) {
        const core::Fault* f = m_ctx.surfaces().sourceOf(state, name, frame, visibility);
        if (!f)
            return m_ctx.error("Cannot export: no fault named " + name);
        core::SurfaceSettings st;
        st.fault = name;
        if (const core::SurfaceSettings* saved = state.surface(name))
            st = *saved;
        requests.push_back({*f, st});
    }
    const Json cmd = vdb ? core::cmd::exportVdb(faults.front(), path)
                         : core::cmd::exportGltf(faults, path, glyphs);
    // Given up when the job ends without settling it (failed or cancelled); held only by
    // closures that live and die on the UI thread.
    auto place = std::make_shared<core::JournalPlace>(m_session);
    m_ctx.jobs().start(
        "Exporting " + fs::path(path).filename().string(),
        [this, frame, requests, path, vdb, cmd, cache = m_ctx.surfaces().cache(),
         frameIndex = state.frame, glyphs,
         at = place->place()](JobControl& control) -> std::function<void()> {
            // Surfaces shown in the views come from their cache, not built again.
            JobInterrupter interrupter(control);
            const core::SurfaceReuse reuse{cache.get(), frameIndex};
            if (vdb)
                core::writeFaultVdb(*frame, requests.front(), path, &interrupter, reuse);
            else
                core::writeFaultsGlb(*frame, requests, path, glyphs, &interrupter, reuse);
            return [this, cmd, path, at] {
                m_session.settleAction(at, cmd); // replayed like any export, where it was asked for
                m_ctx.info("Exported " + path);
            };
        },
        [this, place](const std::string& why) { m_ctx.error("Export failed: " + why); },
        m_ctx.now());
}

void BackgroundExports::csv(core::Json cmd) {
    const std::string path = absolutePath(cmd.value("path", std::string()));
    cmd["path"] = path;
    auto place = std::make_shared<core::JournalPlace>(m_session);
    m_ctx.jobs().start(
        "Exporting " + fs::path(path).filename().string(),
        [this, snapshot = m_session.state(), data = m_session.dataset(), cmd, path,
         at = place->place()](JobControl& control) -> std::function<void()> {
            // Cancel in the status bar stops it between frames; no file is written.
            core::writeFileAtomically(path,
                                      core::exportCsvText(snapshot, data, cmd, {}, [&control] {
                                          if (control.cancelled())
                                              throw std::runtime_error("cancelled");
                                      }));
            return [this, cmd, path, at] {
                m_session.settleAction(at, cmd); // replayed like any export, where it was asked for
                m_ctx.info("Exported " + path);
            };
        },
        [this, place](const std::string& why) { m_ctx.error("Export failed: " + why); },
        m_ctx.now());
}

} // namespace faultline::ui
