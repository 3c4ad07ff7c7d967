// `faultline [PATH]`: the workbench. Until it lands, say what works instead.
#include "app/cli.hpp"

#include <cstdio>

namespace faultline::app {

int runGui(const Args& args) {
    (void)args;
    std::fprintf(stderr, "faultline: the workbench is not built yet; use the headless commands:\n");
    printUsage();
    return 2;
}

} // namespace faultline::app
