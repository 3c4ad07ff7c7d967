#include "core/io/lammps_dump.hpp"

#include "core/util/ascii.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/numeric_table.hpp"
#include "core/io/parsed_columns.hpp"
#include "core/io/text_lines.hpp"

#include <fast_float/fast_float.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace faultline::core {

namespace {

struct DumpHeader {
    std::int64_t timestep = 0;
    std::uint64_t atoms = 0;
    bool haveTimestep = false, haveAtoms = false, haveBox = false;
    SimulationBox box;
    std::vector<std::string> columns;
    bool columnsAssumed = false; // "ITEM: ATOMS" named none (an old-style dump)
};

std::vector<std::string_view> words(std::string_view s) {
    std::vector<std::string_view> out;
    splitBlanks(s, out);
    return out;
}

bool parseDouble(std::string_view w, double& v) {
    if (!w.empty() && w.front() == '+')
        w.remove_prefix(1);
    auto r = fast_float::from_chars(w.data(), w.data() + w.size(), v);
    return r.ec == std::errc() && r.ptr == w.data() + w.size() && std::isfinite(v);
}

bool parseInteger(std::string_view w, std::int64_t& v) {
    double d;
    if (!parseDouble(w, d) || d != std::trunc(d) || std::fabs(d) > 9.0e18)
        return false;
    v = static_cast<std::int64_t>(d);
    return true;
}

// Reads "ITEM:" sections until "ITEM: ATOMS". `next(line)` yields lines, `lineNo()` numbers
// the last line yielded.
template <typename NextLine, typename LineNo>
DumpHeader readHeader(const std::string& path, NextLine next, LineNo lineNo) {
    DumpHeader h;
    std::string_view line;
    auto fail = [&](const std::string& what) -> InputError {
        return InputError(path, InputError::Where::Line, lineNo(), what);
    };
    auto need = [&](const char* what) {
        if (!next(line))
            throw InputError(path, InputError::Where::Line, lineNo() + 1,
                             std::string("file ends where ") + what + " was expected");
        line = trimBlanks(line);
    };
    for (;;) {
        need("an ITEM: line");
        if (line.empty())
            continue;
        if (line.substr(0, 5) != "ITEM:")
            throw fail("expected an 'ITEM:' line, found " + quoteForError(line));
        std::string_view item = trimBlanks(line.substr(5));
        if (item == "TIMESTEP") {
            need("the timestep");
            if (!parseInteger(line, h.timestep))
                throw fail("expected the timestep (an integer), found " + quoteForError(line));
            h.haveTimestep = true;
        } else if (item == "NUMBER OF ATOMS" || item == "NUMBER OF ENTRIES") {
            need("the number of atoms");
            std::int64_t n;
            if (!parseInteger(line, n) || n < 0)
                throw fail("expected the number of atoms (an integer >= 0), found " +
                           quoteForError(line));
            h.atoms = static_cast<std::uint64_t>(n);
            h.haveAtoms = true;
        } else if (item.substr(0, 10) == "BOX BOUNDS") {
            auto flags = words(item.substr(10));
            bool triclinic = false;
            if (flags.size() >= 3 && flags[0] == "xy" && flags[1] == "xz" && flags[2] == "yz") {
                triclinic = true;
                flags.erase(flags.begin(), flags.begin() + 3);
            }
            for (std::size_t a = 0; a < 3 && a < flags.size(); ++a)
                h.box.periodic[a] = flags[a] == "pp";
            double bound[3][3] = {};
            for (int a = 0; a < 3; ++a) {
                need("a box bounds line");
                auto w = words(line);
                const std::size_t want = triclinic ? 3 : 2;
                if (w.size() < want)
                    throw fail("expected " + std::to_string(want) +
                               " numbers for box bounds, found " + quoteForError(line));
                for (std::size_t k = 0; k < want; ++k)
                    if (!parseDouble(w[k], bound[a][k]))
                        throw fail("expected a finite number in box bounds, found " +
                                   quoteForError(w[k]));
            }
            h.box.triclinic = triclinic;
            if (triclinic) {
                // LAMMPS writes the bounding box of the tilted cell; recover the cell itself.
                const double xy = bound[0][2], xz = bound[1][2], yz = bound[2][2];
                h.box.xy = xy;
                h.box.xz = xz;
                h.box.yz = yz;
                h.box.lo[0] = bound[0][0] - std::min({0.0, xy, xz, xy + xz});
                h.box.hi[0] = bound[0][1] - std::max({0.0, xy, xz, xy + xz});
                h.box.lo[1] = bound[1][0] - std::min(0.0, yz);
                h.box.hi[1] = bound[1][1] - std::max(0.0, yz);
            } else {
                h.box.lo[0] = bound[0][0];
                h.box.hi[0] = bound[0][1];
                h.box.lo[1] = bound[1][0];
                h.box.hi[1] = bound[1][1];
            }
            h.box.lo[2] = bound[2][0];
            h.box.hi[2] = bound[2][1];
            h.box.known = true;
            h.haveBox = true;
        } else if (item.substr(0, 5) == "ATOMS" || item.substr(0, 7) == "ENTRIES") {
            for (auto w : words(item.substr(item[0] == 'A' ? 5 : 7)))
                h.columns.emplace_back(w);
            // An old-style dump (LAMMPS before 2009, pizza.py's "dump" reads them) names no
            // columns: the frame reader assumes them from the first row.
            h.columnsAssumed = h.columns.empty();
            if (!h.haveAtoms)
                throw fail("'ITEM: ATOMS' before 'ITEM: NUMBER OF ATOMS'");
            return h;
        } else if (item == "UNITS" || item == "TIME") {
            need("the value of an ITEM: UNITS or TIME line");
        } else {
            throw fail("unknown section " + quoteForError(line));
        }
    }
}

} // namespace

bool looksLikeLammpsDump(std::string_view head) {
    std::size_t i = 0;
    while (i < head.size() &&
           (head[i] == ' ' || head[i] == '\n' || head[i] == '\r' || head[i] == '\t'))
        ++i;
    return head.substr(i, 5) == "ITEM:";
}

std::vector<LammpsFrameIndex> indexLammpsDump(const std::string& path, std::string* partial) {
    return indexTextFrames<LammpsFrameIndex>(
        path, "no 'ITEM: TIMESTEP' frame found: not a LAMMPS dump",
        [&](TextLineReader& reader, LammpsFrameIndex& f, std::size_t) -> std::uint64_t {
            const DumpHeader h = readHeader(
                path, [&](std::string_view& line) { return reader.next(line); },
                [&] { return reader.lineNumber(); });
            f.timestep = h.timestep;
            f.atoms = h.atoms;
            return h.atoms;
        },
        [](const LammpsFrameIndex& f, std::size_t) {
            return std::to_string(f.atoms) + " particle rows of timestep " +
                   std::to_string(f.timestep);
        },
        partial);
}

Frame parseLammpsDumpFrame(const std::string& path, std::string_view text,
                           std::uint64_t firstLine) {
    std::size_t pos = 0;
    std::uint64_t line = firstLine - 1;
    DumpHeader h = readHeader(
        path,
        [&](std::string_view& out) {
            if (pos >= text.size())
                return false;
            const void* nl = std::memchr(text.data() + pos, '\n', text.size() - pos);
            const std::size_t end =
                nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text.data())
                   : text.size();
            out = text.substr(pos, end - pos);
            pos = nl ? end + 1 : text.size();
            ++line;
            return true;
        },
        [&] { return line; });

    if (h.columnsAssumed) {
        // LAMMPS' atom style, as old versions wrote it: id type xs ys zs, with image flags
        // ix iy iz when dump_modify image was on.
        const std::size_t nl = std::min(text.find('\n', pos), text.size());
        std::size_t tokens = 0;
        for (std::size_t k = pos; k < nl; ++k)
            if (text[k] != ' ' && text[k] != '\t' && text[k] != '\r' &&
                (k == pos || text[k - 1] == ' ' || text[k - 1] == '\t'))
                ++tokens;
        h.columns = {"id", "type", "xs", "ys", "zs"};
        if (tokens == 8)
            h.columns.insert(h.columns.end(), {"ix", "iy", "iz"});
        else if (h.atoms > 0 && tokens != 5)
            throw InputError(path, InputError::Where::Line, line + 1,
                             "'ITEM: ATOMS' names no columns, so this is read as an old-style dump "
                             "(LAMMPS' atom style): expected rows of 5 values (id type xs ys zs) "
                             "or 8 (id type xs ys zs ix iy iz), found " +
                                 std::to_string(tokens));
    }
    const auto& cols = h.columns;
    NumericTableSpec spec;
    spec.path = path;
    spec.firstLine = line + 1;
    spec.rows = static_cast<std::size_t>(std::min<std::uint64_t>(h.atoms, text.size() - pos + 1));
    const std::string_view rest = text.substr(pos);
    if (spec.rows < h.atoms) // more rows announced than bytes left: cannot be
        throw InputError(path, InputError::Where::Line, line + 1,
                         "NUMBER OF ATOMS is " + std::to_string(h.atoms) + " but only " +
                             std::to_string(rest.size()) + " bytes follow");
    const NumericTableLayout layout = layoutNumericTable(rest, spec);
    const std::size_t n = spec.rows;
    const std::size_t end = pos + layout.end;
    // A row of c values needs at least 2c bytes. When the rows are too short to hold the count,
    // name the first short row instead of allocating for a count the text cannot hold.
    const std::uint64_t rowBytes = layout.end;
    if (h.atoms > (rowBytes + 1) / (2 * cols.size())) {
        std::size_t p = pos;
        for (std::uint64_t row = 0; row < h.atoms; ++row) {
            const std::size_t nl = std::min(text.find('\n', p), end);
            std::size_t tokens = 0;
            for (std::size_t k = p; k < nl; ++k)
                if (text[k] != ' ' && text[k] != '\t' && text[k] != '\r' &&
                    (k == p || text[k - 1] == ' ' || text[k - 1] == '\t'))
                    ++tokens;
            if (tokens < cols.size())
                throw InputError(path, InputError::Where::Line, line + row + 1,
                                 "expected " + std::to_string(cols.size()) + " values, found " +
                                     std::to_string(tokens));
            p = nl + 1;
        }
    }
    // Anything after the rows must be blank or the next frame.
    {
        std::size_t k = end;
        while (k < text.size() &&
               (text[k] == ' ' || text[k] == '\n' || text[k] == '\r' || text[k] == '\t'))
            ++k;
        if (k < text.size() && text.compare(k, 5, "ITEM:") != 0)
            throw InputError(path, InputError::Where::Line, line + n + 1,
                             "more rows than the " + std::to_string(n) + " announced");
    }

    auto find = [&](std::initializer_list<const char*> names) -> int {
        for (const char* name : names)
            for (std::size_t c = 0; c < cols.size(); ++c)
                if (cols[c] == name)
                    return static_cast<int>(c);
        return -1;
    };
    // Positions: unwrapped or wrapped, then scaled ones converted with the box.
    const char* posNames[4][3] = {
        {"x", "y", "z"}, {"xu", "yu", "zu"}, {"xs", "ys", "zs"}, {"xsu", "ysu", "zsu"}};
    int posCol[3] = {-1, -1, -1};
    bool scaled = false;
    for (int set = 0; set < 4 && posCol[0] < 0; ++set) {
        int c[3] = {find({posNames[set][0]}), find({posNames[set][1]}), find({posNames[set][2]})};
        if (c[0] >= 0 && c[1] >= 0 && c[2] >= 0) {
            std::copy(c, c + 3, posCol);
            scaled = set >= 2;
        }
    }
    if (posCol[0] < 0)
        throw InputError(path, InputError::Where::Line, firstLine,
                         "no position columns: expected x y z, xu yu zu, xs ys zs or xsu ysu zsu "
                         "in 'ITEM: ATOMS'");
    if (scaled && !h.haveBox)
        throw InputError(path, InputError::Where::Line, firstLine,
                         "scaled positions need 'ITEM: BOX BOUNDS'");
    const int idCol = find({"id"});
    const int radiusCol = find({"radius"});
    const int diameterCol = radiusCol < 0 ? find({"diameter"}) : -1;

    Frame frame;
    frame.columnsAssumed = h.columnsAssumed;
    frame.timestep = h.timestep;
    frame.box = h.box;

    std::vector<TableColumnTarget> targets(cols.size());
    std::vector<std::vector<float>> attributeValues(cols.size());
    std::vector<bool> isAttribute(cols.size(), false);
    {
        std::vector<std::vector<float>*> floatColumns{&frame.x, &frame.y, &frame.z, &frame.radius};
        for (std::size_t c = 0; c < cols.size(); ++c) {
            const int ci = static_cast<int>(c);
            if (ci != idCol && ci != posCol[0] && ci != posCol[1] && ci != posCol[2] &&
                ci != radiusCol && ci != diameterCol)
                floatColumns.push_back(&attributeValues[c]);
        }
        resizeColumnsInParallel(floatColumns, {&frame.ids}, n);
    }
    std::vector<float>* axes[3] = {&frame.x, &frame.y, &frame.z};
    for (std::size_t c = 0; c < cols.size(); ++c) {
        TableColumnTarget& t = targets[c];
        t.name = cols[c];
        const int ci = static_cast<int>(c);
        if (ci == idCol) {
            t.kind = TableColumnTarget::Kind::Int64;
            t.ints = frame.ids.data();
        } else if (ci == posCol[0] || ci == posCol[1] || ci == posCol[2]) {
            const int a = ci == posCol[0] ? 0 : ci == posCol[1] ? 1 : 2;
            t.kind = TableColumnTarget::Kind::Float;
            t.floats = axes[a]->data();
            t.requireFinite = true;
        } else if (ci == radiusCol || ci == diameterCol) {
            t.kind = TableColumnTarget::Kind::Float;
            t.floats = frame.radius.data();
            t.requireFinite = true;
        } else {
            bool duplicate = false;
            for (std::size_t k = 0; k < c; ++k)
                duplicate |= cols[k] == cols[c];
            if (duplicate)
                throw InputError(path, InputError::Where::Line, firstLine,
                                 "column '" + cols[c] + "' appears twice in 'ITEM: ATOMS'");
            isAttribute[c] = true;
            t.kind = TableColumnTarget::Kind::Float;
            t.floats = attributeValues[c].data();
        }
    }

    parseNumericTable(rest, layout, spec, targets);

    if (scaled) {
        const SimulationBox& b = h.box;
        const double lx = b.hi[0] - b.lo[0], ly = b.hi[1] - b.lo[1], lz = b.hi[2] - b.lo[2];
        for (std::size_t i = 0; i < n; ++i) {
            const double xs = frame.x[i], ys = frame.y[i], zs = frame.z[i];
            frame.x[i] = static_cast<float>(b.lo[0] + xs * lx + ys * b.xy + zs * b.xz);
            frame.y[i] = static_cast<float>(b.lo[1] + ys * ly + zs * b.yz);
            frame.z[i] = static_cast<float>(b.lo[2] + zs * lz);
        }
    }
    completeParsedFrame(frame,
                        {cols, targets, attributeValues, isAttribute, idCol >= 0,
                         radiusCol >= 0     ? ParsedColumns::Radius::Radius
                         : diameterCol >= 0 ? ParsedColumns::Radius::Diameter
                                            : ParsedColumns::Radius::Missing},
                        path, firstLine);
    return frame;
}

} // namespace faultline::core
