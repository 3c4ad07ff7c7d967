// The usage text both executables print.
#include "app/cli.hpp"

#include <cstdio>

void faultline::app::printUsage() {
    std::puts(
        "usage: faultline [PATH]                 open the workbench (on PATH, or the demo model)\n"
        "       faultline info PATH...           format, frames, spheres, columns and box of data "
        "files\n"
        "       faultline replay JOURNAL [--data PATH...] [--out DIR] [--frames A:B | --shard "
        "K/N] [--strict]\n"
        "                                        run a recorded journal headless; exit 0 when "
        "every\n"
        "                                        expectation holds (--data: the same analysis on "
        "other data;\n"
        "                                        --frames/--shard: per-frame work on those frames "
        "only;\n"
        "                                        --strict: a threshold or colouring on a "
        "variable\n"
        "                                        the data lacks fails the replay, not only "
        "warns)\n"
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
