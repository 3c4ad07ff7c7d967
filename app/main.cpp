// faultline: the command line; the workbench and the OpenGL commands live in faultline-app.
#include "app/cli.hpp"

#include <cstdio>
#include <exception>
#include <string>

using namespace faultline::app;

// The commands that read and write files only (info, merge, generate, help) run in this small
// program, which loads no GUI, OpenGL, OpenVDB or video libraries: `faultline info` starts in a
// few milliseconds. Everything else (the workbench, replay, render) runs in faultline-app beside
// it, which this program becomes (exec) with the same arguments.
int main(int argc, char** argv) {
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
            if (cmd == "-h" || cmd == "--help" || cmd == "help") {
                printUsage();
                return 0;
            }
        }
        return runFullApp(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline: %s\n", e.what());
        return 1;
    }
}
