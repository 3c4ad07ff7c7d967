// Ops that need more than core: registered on every session the app creates.
#include "app/cli.hpp"

#include "core/session/session.hpp"

#if FAULTLINE_WITH_GUI
#include "ui/viewport/session_figure.hpp"
#endif

namespace faultline::app {

void registerAppOps(core::Session& session) {
#if FAULTLINE_WITH_GUI
    ui::registerRenderOp(session);
#else
    (void)session; // a build without the GUI keeps core's "render: not available" answer
#endif
}

} // namespace faultline::app
