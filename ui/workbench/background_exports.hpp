// Exports that take a while (CSV read over every frame, fault surfaces as OpenVDB or glTF),
// written on a worker thread with progress and Cancel in the status bar. Each holds its place in
// the journal from when it was asked for (Session::reserveAction) and records its op there once
// the file is written, so a replay exports the same at the same point; a failed or cancelled
// export gives its place up.
#pragma once

#include "core/session/command_args.hpp" // core::Json

#include <string>
#include <vector>

namespace faultline::core {
class Session;
}

namespace faultline::ui {

class PanelContext;

class BackgroundExports {
  public:
    // `ctx` gives the jobs, the surfaces shown (their cache), the clock and the messages.
    BackgroundExports(core::Session& session, PanelContext& ctx) : m_session(session), m_ctx(ctx) {}

    // export.csv (tracks and metrics read every frame) with a copy of the state.
    void csv(core::Json cmd);
    // Fault surfaces to a .vdb (one fault) or a .glb (several; with `glyphs`, their spheres as
    // instanced glyphs too); surfaces the views show come from their cache.
    void surfaces(std::vector<std::string> faults, const std::string& path, bool vdb, bool glyphs);

  private:
    core::Session& m_session;
    PanelContext& m_ctx;
};

} // namespace faultline::ui
