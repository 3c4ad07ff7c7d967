// faultline: GUI entry and CLI subcommands (info, and more as features land).
#include "app/cli.hpp"

#include <cstdio>
#include <exception>
#include <string>

using namespace faultline::app;

void faultline::app::printUsage() {
    std::puts(
        "usage: faultline [PATH]                 open the workbench (on PATH, or the demo model)\n"
        "       faultline info PATH...           format, frames, spheres, columns and box of data "
        "files\n"
        "       faultline replay JOURNAL [--data PATH...] [--out DIR] [--frames A:B | --shard "
        "K/N]\n"
        "                                        run a recorded journal headless; exit 0 when "
        "every\n"
        "                                        expectation holds (--data: the same analysis on "
        "other data;\n"
        "                                        --frames/--shard: per-frame work on those frames "
        "only)\n"
        "       faultline merge OUT.csv SHARD.csv...  shards' CSVs as the unsharded run writes "
        "them\n"
        "       faultline render SESSION|JOURNAL --out FIG.png [--view V] [--frame N] [--size "
        "WxH]\n"
        "                                        [--transparent] [--data PATH...]  a figure, "
        "offscreen\n"
        "       faultline generate --demo        build the demo model once (per-user data folder)\n"
        "       faultline generate ... --out DIR a bonded DEM extension model or known planar "
        "faults\n"
        "                                        (faultline generate --help for options)\n"
        "       faultline render-data FILE --out X.png [--color VAR] [--map NAME] [--size WxH] "
        "...\n"
        "                                        render one frame to a PNG (developer tool)\n"
        "\n"
        "PATH may be a LAMMPS/LIGGGHTS dump (.gz too; many frames per file; '%' for per-processor\n"
        "files), a VTK legacy or XML file (.vtk .vtu .vtp .pvd), or a CSV table with x,y,z "
        "columns.\n"
        "Quote glob patterns: faultline info 'run1/dump.*.gz'");
}

int main(int argc, char** argv) {
    Args args(argv + 1, argv + argc);
    try {
        if (!args.empty()) {
            const std::string cmd = args.front();
            Args rest(args.begin() + 1, args.end());
            if (cmd == "info")
                return runInfo(rest);
            if (cmd == "replay")
                return runReplay(rest);
            if (cmd == "render")
                return runRender(rest);
            if (cmd == "merge")
                return runMerge(rest);
            if (cmd == "generate")
                return runGenerate(rest);
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
