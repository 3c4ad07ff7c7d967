// Ops on the whole session: session.open (load a *.faultline.json, its data optionally at another
// place; Session::apply starts a new history after it, so it is no undo step) and
// session.restore (a whole state given inline).
#include "core/session/session_ops.hpp"

namespace faultline::core::detail {

namespace {

// Makes `next` the session's state, opening its data first (nothing changes when that fails).
// Returns the command that restores the state as it was.
Json replaceWith(Session& s, SessionState next, const std::string& op) {
    if (!s.dataOverride().empty() && !next.dataPaths.empty())
        next.dataPaths = s.dataOverride(); // replay --data: the same analysis on another run
    std::shared_ptr<Dataset> ds = s.dataset();
    const bool sameData = ds && next.dataPaths == s.state().dataPaths;
    if (!sameData) {
        ds.reset();
        if (!next.dataPaths.empty()) {
            try {
                ds = s.openDataset(next.dataPaths);
            } catch (const InputError& e) {
                throw CommandError(op + ": " + e.what());
            }
        }
    }
    if (ds && next.frame >= ds->frameCount())
        throw CommandError(op + ": the session shows frame " + std::to_string(next.frame) +
                           " but the data has " + std::to_string(ds->frameCount()) + " frames");
    if (!ds && !next.dataPaths.empty())
        throw CommandError(op + ": the data could not be opened");
    Json inverse = {{"op", "session.restore"}, {"state", sessionToJson(s.state(), "")}};
    s.mutableState() = std::move(next);
    if (!sameData)
        s.setDataset(std::move(ds));
    return inverse;
}

} // namespace

void registerSessionOps(OpRegistry& ops) {
    addStateOp(ops, "session.open", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"path", "data"});
        const std::string path = s.inputPath(args::string(cmd, "path"));
        SessionState next;
        try {
            next = loadSessionFile(path);
        } catch (const InputError& e) {
            throw CommandError(std::string("session.open: ") + e.what());
        }
        // "data": where the session's data is now, when it moved since the session was saved.
        if (cmd.contains("data")) {
            std::vector<std::string> data = args::strings(cmd, "data");
            if (data.empty())
                throw CommandError("session.open: \"data\" is empty");
            for (auto& p : data)
                p = s.inputPath(p);
            next.dataPaths = std::move(data);
        }
        Json inverse = replaceWith(s, std::move(next), "session.open");
        s.markSavedAfterThisOp(); // what is on disk
        return inverse;
    });
    addStateOp(ops, "session.restore", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"state"});
        const Json& doc = args::require(cmd, "state");
        SessionState next = asCommand("session.restore",
                                      [&] { return sessionFromJson(doc, "", "session.restore"); });
        return replaceWith(s, std::move(next), "session.restore");
    });
}

} // namespace faultline::core::detail
