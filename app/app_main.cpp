// faultline-app: the workbench and the commands that need OpenGL, OpenVDB or video (replay,
// render, render-data); `faultline` runs it for them (main.cpp). It answers the light commands
// too, so it can stand alone.
#include "app/cli.hpp"
#include "core/util/malloc_huge_pages.hpp"

#include <cstdio>
#include <exception>
#include <string>

using namespace faultline::app;

int main(int argc, char** argv) {
    // Large blocks on huge pages: frames load several times faster in a virtual machine.
    faultline::core::restartWithMallocHugePages(argv);
    Args args(argv + 1, argv + argc);
    try {
        if (!args.empty()) {
            const std::string cmd = args.front();
            Args rest(args.begin() + 1, args.end());
            if (cmd == "info")
                return runInfo(rest);
            if (cmd == "merge")
                return runMerge(rest);
            if (cmd == "generate")
                return runGenerate(rest);
            if (cmd == "replay")
                return runReplay(rest);
            if (cmd == "render")
                return runRender(rest);
            if (cmd == "render-data")
                return runRenderData(rest);
            if (cmd == "-h" || cmd == "--help" || cmd == "help") {
                printUsage();
                return 0;
            }
        }
        return runGui(args);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline: %s\n", e.what());
        return 1;
    }
}
