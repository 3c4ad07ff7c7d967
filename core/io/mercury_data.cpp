#include "core/io/mercury_data.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/text_lines.hpp"
#include "core/util/ascii.hpp"

#include <fast_float/fast_float.h>

#include <charconv>
#include <cmath>

namespace faultline::core {

namespace {

bool number(std::string_view w, double& v) {
    const auto r = fast_float::from_chars(w.data(), w.data() + w.size(), v);
    return r.ec == std::errc() && r.ptr == w.data() + w.size() && std::isfinite(v);
}

bool count(std::string_view w, std::uint64_t& n) {
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), n);
    return ec == std::errc() && end == w.data() + w.size();
}

struct Header {
    std::uint64_t particles = 0;
    double time = 0;
    int dimensions = 3;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

// The header line, or why it is not one.
bool readHeader(std::string_view line, Header& h, std::string& why) {
    std::vector<std::string_view> w;
    splitBlanks(line, w);
    if (w.size() != 6 && w.size() != 8) {
        why = "expected a time step header of 8 numbers (N time xmin ymin zmin xmax ymax zmax) "
              "or 6 in 2-D, found " +
              std::to_string(w.size()) + " values";
        return false;
    }
    if (!count(w[0], h.particles)) {
        why = "expected the number of particles first, found " + quoteForError(w[0]);
        return false;
    }
    double v[8] = {};
    for (std::size_t k = 1; k < w.size(); ++k)
        if (!number(w[k], v[k])) {
            why = "header value " + std::to_string(k + 1) + ": expected a finite number, found " +
                  quoteForError(w[k]);
            return false;
        }
    h.time = v[1];
    h.dimensions = w.size() == 8 ? 3 : 2;
    if (h.dimensions == 3) {
        for (int a = 0; a < 3; ++a)
            h.lo[a] = v[2 + a], h.hi[a] = v[5 + a];
    } else {
        h.lo[0] = v[2], h.lo[1] = v[3], h.hi[0] = v[4], h.hi[1] = v[5];
    }
    return true;
}

} // namespace

bool looksLikeMercuryData(std::string_view head) {
    std::size_t pos = 0;
    auto next = [&](std::string_view& line) {
        while (pos < head.size()) {
            std::size_t nl = head.find('\n', pos);
            if (nl == std::string_view::npos)
                nl = head.size();
            line = head.substr(pos, nl - pos);
            pos = nl + 1;
            if (line.find_first_not_of(" \t\r") != std::string_view::npos)
                return true;
        }
        return false;
    };
    std::string_view line;
    Header h;
    std::string why;
    if (!next(line) || !readHeader(line, h, why))
        return false;
    if (h.particles == 0)
        return true;
    if (!next(line))
        return false;
    std::vector<std::string_view> w;
    splitBlanks(line, w);
    if (w.size() != (h.dimensions == 3 ? 14u : 8u))
        return false;
    double v;
    for (auto t : w)
        if (!number(t, v))
            return false;
    return true;
}

std::vector<MercuryFrameIndex> indexMercuryData(const std::string& path, std::string* partial) {
    return indexTextFrames<MercuryFrameIndex>(
        path, "no MercuryDPM time step found",
        [&](TextLineReader& reader, MercuryFrameIndex& f, std::size_t count) -> std::uint64_t {
            std::string_view line;
            reader.next(line);
            Header h;
            std::string why;
            if (!readHeader(line, h, why))
                throw InputError(path, InputError::Where::Line, reader.lineNumber(),
                                 "time step " + std::to_string(count) + ": " + why);
            f.particles = h.particles;
            f.time = h.time;
            return h.particles;
        },
        [](const MercuryFrameIndex& f, std::size_t count) {
            return "the " + std::to_string(f.particles) + " particle rows of time step " +
                   std::to_string(count);
        },
        partial);
}

Frame parseMercuryDataFrame(const std::string& path, std::string_view text,
                            std::uint64_t firstLine) {
    TextCursor cursor{text, 0, firstLine - 1};
    auto next = [&](std::string_view& line) { return cursor.next(line); };
    std::string_view line;
    while (next(line) && line.find_first_not_of(" \t\r") == std::string_view::npos) {
    }
    Header h;
    std::string why;
    if (!readHeader(line, h, why))
        throw InputError(path, InputError::Where::Line, cursor.line, why);
    const std::uint64_t rest = cursor.left();
    if (h.particles > rest / 16 + 1) // a row holds at least 8 values of 2 bytes
        throw InputError(path, InputError::Where::Line, cursor.line,
                         "the header announces " + std::to_string(h.particles) +
                             " particles but only " + std::to_string(rest) + " bytes follow");
    const bool is3d = h.dimensions == 3;
    const std::size_t width = is3d ? 14 : 8;
    const std::size_t n = static_cast<std::size_t>(h.particles);
    Frame frame;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.assign(n, 0.0f);
    frame.radius.resize(n);
    frame.ids.resize(n);
    frame.idsAreRowNumbers = true;
    // Columns after the position: (name, index in the row).
    const std::vector<std::pair<const char*, std::size_t>> attrs3 = {{"vx", 3},
                                                                     {"vy", 4},
                                                                     {"vz", 5},
                                                                     {"orientation_x", 7},
                                                                     {"orientation_y", 8},
                                                                     {"orientation_z", 9},
                                                                     {"angular_velocity_x", 10},
                                                                     {"angular_velocity_y", 11},
                                                                     {"angular_velocity_z", 12}};
    const std::vector<std::pair<const char*, std::size_t>> attrs2 = {
        {"vx", 2}, {"vy", 3}, {"orientation", 5}, {"angular_velocity", 6}};
    const auto& attrs = is3d ? attrs3 : attrs2;
    std::vector<AttributeColumn> columns(attrs.size() + 1);
    for (std::size_t k = 0; k < attrs.size(); ++k) {
        columns[k].name = attrs[k].first;
        columns[k].floats.resize(n);
    }
    AttributeColumn& species = columns.back();
    species.name = "species";
    species.type = ColumnType::Int32;
    species.ints.resize(n);
    const std::size_t radiusAt = is3d ? 6 : 4;
    std::vector<std::string_view> w;
    for (std::size_t row = 0; row < n; ++row) {
        if (!next(line))
            throw InputError(path, InputError::Where::Line, cursor.line + 1,
                             "file ends after " + std::to_string(row) + " of " + std::to_string(n) +
                                 " particle rows");
        splitBlanks(line, w);
        if (w.size() != width)
            throw InputError(path, InputError::Where::Line, cursor.line,
                             "expected " + std::to_string(width) + " values (a " +
                                 std::to_string(h.dimensions) + "-D MercuryDPM row), found " +
                                 std::to_string(w.size()));
        double v[14];
        for (std::size_t k = 0; k < width; ++k)
            if (!number(w[k], v[k]))
                throw InputError(path, InputError::Where::Line, cursor.line,
                                 "value " + std::to_string(k + 1) +
                                     ": expected a finite number, found " + quoteForError(w[k]));
        frame.x[row] = static_cast<float>(v[0]);
        frame.y[row] = static_cast<float>(v[1]);
        if (is3d)
            frame.z[row] = static_cast<float>(v[2]);
        if (!(v[radiusAt] > 0))
            throw InputError(path, InputError::Where::Line, cursor.line,
                             "the radius must be positive, found " + quoteForError(w[radiusAt]));
        frame.radius[row] = static_cast<float>(v[radiusAt]);
        frame.ids[row] = static_cast<std::int64_t>(row);
        for (std::size_t k = 0; k < attrs.size(); ++k)
            columns[k].floats[row] = static_cast<float>(v[attrs[k].second]);
        const double s = v[width - 1];
        if (s != std::trunc(s) || std::fabs(s) > 2.0e9)
            throw InputError(path, InputError::Where::Line, cursor.line,
                             "the species index must be a whole number, found " +
                                 quoteForError(w[width - 1]));
        species.ints[row] = static_cast<std::int32_t>(s);
    }
    frame.attributes = std::move(columns);
    for (int a = 0; a < 3; ++a) {
        frame.box.lo[a] = h.lo[a];
        frame.box.hi[a] = h.hi[a];
    }
    frame.box.known = is3d || h.hi[0] > h.lo[0];
    try {
        frame.finalize();
    } catch (const std::invalid_argument& e) {
        throw InputError(path, InputError::Where::Line, firstLine, e.what());
    }
    return frame;
}

} // namespace faultline::core
