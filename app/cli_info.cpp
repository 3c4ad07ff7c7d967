// `faultline info PATH...`: how a user checks that a file reads right.
#include "app/cli.hpp"

#include "core/data/dataset.hpp"
#include "core/io/input_error.hpp"
#include "core/model/packing.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace faultline::app {

namespace {

// printf into a string: the report is printed whole once every frame has read, so an error found
// late never leaves half a report behind it.
[[gnu::format(printf, 2, 3)]] void appendf(std::string& out, const char* format, ...) {
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    if (n > 0) {
        const std::size_t at = out.size();
        out.resize(at + static_cast<std::size_t>(n) + 1);
        std::vsnprintf(out.data() + at, static_cast<std::size_t>(n) + 1, format, again);
        out.pop_back(); // the terminating NUL
    }
    va_end(again);
}

void printFrame(std::string& out, const core::Frame& f) {
    appendf(out, "  spheres: %zu%s\n", f.size(),
            f.idsAreRowNumbers ? " (no id column: ids are row numbers)" : "");
    appendf(out, "  radius: %s", f.radiusIsDefault ? "none in file, default " : "");
    if (f.size() > 0) {
        auto [mn, mx] = std::minmax_element(f.radius.begin(), f.radius.end());
        appendf(out, "%g .. %g\n", *mn, *mx);
    } else {
        appendf(out, "-\n");
    }
    const auto& b = f.box;
    appendf(out, "  box: [%g %g] x [%g %g] x [%g %g]%s%s\n", b.lo[0], b.hi[0], b.lo[1], b.hi[1],
            b.lo[2], b.hi[2], b.triclinic ? " triclinic" : "",
            b.known ? "" : " (bounds of the centres)");
    appendf(out, "  centres: [%g %g] x [%g %g] x [%g %g]\n", f.centreMin()[0], f.centreMax()[0],
            f.centreMin()[1], f.centreMax()[1], f.centreMin()[2], f.centreMax()[2]);
    if (const std::string note = core::radiiUnitNote(f); !note.empty())
        appendf(out, "  note: %s\n", note.c_str());
    appendf(out, "  columns: %zu\n", f.attributes.size());
    if (f.columnsAssumed)
        appendf(out, "  note: the file names no columns ('ITEM: ATOMS' alone, an old-style dump);\n"
                     "        read as LAMMPS' atom style: id type xs ys zs (then ix iy iz)\n");
    for (const auto& c : f.attributes)
        appendf(out, "    %-24s %-6s %g .. %g\n", c.name.c_str(), c.isInteger() ? "int" : "float",
                c.min, c.max);
}
} // namespace

int runInfo(const Args& args) {
    if (args.empty()) {
        std::fprintf(stderr, "usage: faultline info PATH...\n");
        return 2;
    }
    int status = 0;
    for (const auto& path : args) {
        std::string out;
        try {
            auto ds = core::Dataset::open({path});
            const auto& first = ds->location(0);
            appendf(out, "%s\n  format: %s\n  frames: %zu", path.c_str(),
                    std::string(core::formatName(first.format)).c_str(), ds->frameCount());
            if (ds->frameCount() > 1)
                appendf(out, " (timesteps %lld .. %lld)", static_cast<long long>(first.timestep),
                        static_cast<long long>(ds->location(ds->frameCount() - 1).timestep));
            appendf(out, "\n");
            for (const auto& note : ds->notes())
                appendf(out, "  note: %s\n", note.c_str());
            if (ds->files().size() > 1)
                appendf(out, "  files: %zu\n", ds->files().size());
            appendf(out, "  frame 0 (timestep %lld):\n", static_cast<long long>(first.timestep));
            printFrame(out, *ds->frame(0));
            // Every other frame must read too: a user asks info to know the whole file is sound.
            for (std::size_t k = 1; k < ds->frameCount(); ++k) {
                auto f = ds->frame(k);
                if (ds->location(k).particleCount && f->size() != ds->location(k).particleCount)
                    throw core::InputError(path, "frame " + std::to_string(k) + " size mismatch");
            }
            std::fputs(out.c_str(), stdout);
        } catch (const core::InputError& e) {
            std::fprintf(stderr, "faultline info: %s\n", e.what());
            status = 1;
        }
    }
    return status;
}

} // namespace faultline::app
