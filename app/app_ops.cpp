// Ops that need more than core: registered on every session the app creates.
#include "app/cli.hpp"

#include "core/session/session.hpp"

namespace faultline::app {

void registerAppOps(core::Session& session) {
    (void)session; // "render" is registered here once the renderer lands.
}

} // namespace faultline::app
