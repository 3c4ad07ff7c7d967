#include "core/io/extxyz.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/text_lines.hpp"
#include "core/util/ascii.hpp"

#include <fast_float/fast_float.h>

#include <charconv>
#include <cmath>
#include <map>
#include <optional>

namespace faultline::core {

namespace {

// A whole non-negative count filling the (trimmed) line.
std::optional<std::uint64_t> countLine(std::string_view line) {
    line = trimBlanks(line);
    std::uint64_t n = 0;
    if (line.empty())
        return std::nullopt;
    const auto [end, ec] = std::from_chars(line.data(), line.data() + line.size(), n);
    if (ec != std::errc() || end != line.data() + line.size())
        return std::nullopt;
    return n;
}

bool isNumber(std::string_view w) {
    double v;
    const auto r = fast_float::from_chars(w.data(), w.data() + w.size(), v);
    return r.ec == std::errc() && r.ptr == w.data() + w.size();
}

// key=value pairs of an extended XYZ comment line; values may be "quoted" or {braced}.
std::map<std::string, std::string> commentPairs(std::string_view line) {
    std::map<std::string, std::string> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
            ++i;
        const std::size_t k = i;
        while (i < line.size() && line[i] != '=' && line[i] != ' ' && line[i] != '\t')
            ++i;
        std::string key(line.substr(k, i - k));
        if (i >= line.size() || line[i] != '=') {
            if (!key.empty())
                out[key] = "T"; // a bare key is a true flag
            continue;
        }
        ++i; // '='
        std::string value;
        if (i < line.size() && (line[i] == '"' || line[i] == '{')) {
            const char close = line[i] == '"' ? '"' : '}';
            const std::size_t end = line.find(close, i + 1);
            value = std::string(
                line.substr(i + 1, (end == std::string_view::npos ? line.size() : end) - i - 1));
            i = end == std::string_view::npos ? line.size() : end + 1;
        } else {
            const std::size_t v = i;
            while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
                ++i;
            value = std::string(line.substr(v, i - v));
        }
        out[key] = value;
    }
    return out;
}

struct Property {
    std::string name;
    char type = 'R';         // R I L S
    std::size_t columns = 1; // how many row values it takes
    std::size_t first = 0;   // its first value's index in a row
};

std::vector<Property> parseProperties(const std::string& path, std::uint64_t line,
                                      const std::string& spec) {
    std::vector<Property> out;
    std::vector<std::string> parts;
    std::size_t s = 0;
    for (;;) {
        const std::size_t c = spec.find(':', s);
        parts.push_back(spec.substr(s, c == std::string::npos ? std::string::npos : c - s));
        if (c == std::string::npos)
            break;
        s = c + 1;
    }
    if (parts.size() % 3 != 0)
        throw InputError(path, InputError::Where::Line, line,
                         "Properties=" + quoteForError(spec, 80) +
                             ": expected name:type:columns triples (for example "
                             "species:S:1:pos:R:3)");
    std::size_t column = 0;
    for (std::size_t k = 0; k < parts.size(); k += 3) {
        Property p;
        p.name = parts[k];
        const std::string& type = parts[k + 1];
        if (p.name.empty() || type.size() != 1 ||
            std::string("RILS").find(type[0]) == std::string::npos)
            throw InputError(path, InputError::Where::Line, line,
                             "Properties: property " + quoteForError(p.name) + " has type " +
                                 quoteForError(type) + ": expected R, I, L or S");
        p.type = type[0];
        const auto n = countLine(parts[k + 2]);
        if (!n || *n < 1 || *n > 64)
            throw InputError(path, InputError::Where::Line, line,
                             "Properties: property " + quoteForError(p.name) +
                                 " has column count " + quoteForError(parts[k + 2]) +
                                 ": expected 1 to 64");
        p.columns = static_cast<std::size_t>(*n);
        p.first = column;
        column += p.columns;
        out.push_back(std::move(p));
    }
    return out;
}

std::int64_t timestepOf(const std::map<std::string, std::string>& pairs, std::int64_t fallback) {
    for (const char* key : {"Timestep", "timestep", "step", "Step", "time_step"}) {
        auto it = pairs.find(key);
        if (it == pairs.end())
            continue;
        std::int64_t v = 0;
        const auto [end, ec] =
            std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
        if (ec == std::errc() && end == it->second.data() + it->second.size())
            return v;
    }
    return fallback;
}

} // namespace

bool looksLikeXyz(std::string_view head) {
    TextCursor cursor{head};
    auto next = [&](std::string_view& line) { return cursor.next(line); };
    std::string_view count, comment, row;
    if (!next(count) || !countLine(count) || !next(comment))
        return false;
    if (comment.find("Properties=") != std::string_view::npos)
        return true;
    if (!next(row))
        return *countLine(count) == 0;
    std::vector<std::string_view> w;
    splitBlanks(row, w);
    // Plain XYZ: "Element x y z".
    return w.size() >= 4 && !isNumber(w[0]) && isNumber(w[1]) && isNumber(w[2]) && isNumber(w[3]);
}

std::vector<XyzFrameIndex> indexXyz(const std::string& path, std::string* partial) {
    return indexTextFrames<XyzFrameIndex>(
        path, "no XYZ frame found",
        [&](TextLineReader& reader, XyzFrameIndex& f, std::size_t count) -> std::uint64_t {
            std::string_view line;
            reader.next(line);
            const auto n = countLine(line);
            if (!n)
                throw InputError(path, InputError::Where::Line, reader.lineNumber(),
                                 "expected the number of particles of frame " +
                                     std::to_string(count) + ", found " + quoteForError(line));
            f.atoms = *n;
            if (!reader.next(line))
                throw InputError(path, InputError::Where::Line, reader.lineNumber() + 1,
                                 "file ends where frame " + std::to_string(count) +
                                     "'s comment line was expected");
            f.timestep = timestepOf(commentPairs(line), std::int64_t(count));
            return f.atoms;
        },
        [](const XyzFrameIndex& f, std::size_t count) {
            return "the " + std::to_string(f.atoms) + " particle rows of frame " +
                   std::to_string(count);
        },
        partial);
}

Frame parseXyzFrame(const std::string& path, std::string_view text, std::uint64_t firstLine) {
    TextCursor cursor{text, 0, firstLine - 1};
    auto next = [&](std::string_view& line) { return cursor.next(line); };
    std::string_view line;
    while (next(line) && trimBlanks(line).empty()) {
    }
    const auto n = countLine(line);
    if (!n)
        throw InputError(path, InputError::Where::Line, cursor.line,
                         "expected the number of particles, found " + quoteForError(line));
    // Each row has at least 2 bytes per value and 4 values: refuse counts the text cannot hold.
    if (*n > (cursor.left()) / 8 + 1)
        throw InputError(path, InputError::Where::Line, cursor.line,
                         "the frame announces " + std::to_string(*n) + " particles but only " +
                             std::to_string(cursor.left()) + " bytes follow");
    if (!next(line))
        throw InputError(path, InputError::Where::Line, cursor.line + 1,
                         "file ends where the comment line was expected");
    const std::uint64_t commentLine = cursor.line;
    const auto pairs = commentPairs(line);
    std::vector<Property> props;
    if (auto it = pairs.find("Properties"); it != pairs.end())
        props = parseProperties(path, commentLine, it->second);
    else
        props = parseProperties(path, commentLine, "species:S:1:pos:R:3");
    std::size_t width = 0;
    for (const auto& p : props)
        width += p.columns;

    auto findProp = [&](std::initializer_list<const char*> names) -> const Property* {
        for (const char* name : names)
            for (const auto& p : props)
                if (asciiLower(p.name) == asciiLower(name))
                    return &p;
        return nullptr;
    };
    const Property* posProp = findProp({"pos", "positions", "position"});
    if (!posProp || posProp->columns != 3 || posProp->type != 'R')
        throw InputError(path, InputError::Where::Line, commentLine,
                         "no positions: expected a property pos:R:3 in Properties=");
    const Property* idProp = findProp({"id", "identifier", "particle_id"});
    if (idProp && (idProp->type != 'I' || idProp->columns != 1))
        idProp = nullptr;
    const Property* radiusProp = findProp({"radius", "radii", "rad"});
    bool diameter = false;
    if (!radiusProp || radiusProp->type != 'R' || radiusProp->columns != 1) {
        radiusProp = findProp({"diameter", "diam"});
        diameter = radiusProp != nullptr;
        if (radiusProp && (radiusProp->type != 'R' || radiusProp->columns != 1))
            radiusProp = nullptr, diameter = false;
    }

    Frame frame;
    frame.timestep = timestepOf(pairs, 0);
    const std::size_t count = static_cast<std::size_t>(*n);
    frame.x.resize(count);
    frame.y.resize(count);
    frame.z.resize(count);
    frame.radius.assign(count, kDefaultRadius);
    frame.radiusIsDefault = radiusProp == nullptr;
    frame.idsAreRowNumbers = idProp == nullptr;
    frame.ids.resize(count);
    // Attribute columns: every other property value (a vector's components as name_x...).
    struct Attr {
        std::size_t column;
        char type;
        AttributeColumn data;
        std::map<std::string, int, std::less<>> names; // S: species -> code
    };
    std::vector<Attr> attrs;
    static const char* kAxes[] = {"_x", "_y", "_z"};
    for (const auto& p : props) {
        if (&p == posProp || &p == idProp || &p == radiusProp)
            continue;
        for (std::size_t c = 0; c < p.columns; ++c) {
            Attr a;
            a.column = p.first + c;
            a.type = p.type;
            a.data.name = p.columns == 1   ? p.name
                          : p.columns == 3 ? p.name + kAxes[c]
                                           : p.name + "_" + std::to_string(c);
            a.data.type = p.type == 'R' ? ColumnType::Float32 : ColumnType::Int32;
            if (p.type == 'R')
                a.data.floats.resize(count);
            else
                a.data.ints.resize(count);
            attrs.push_back(std::move(a));
        }
    }
    std::vector<std::string_view> w;
    for (std::size_t row = 0; row < count; ++row) {
        if (!next(line))
            throw InputError(path, InputError::Where::Line, cursor.line + 1,
                             "file ends after " + std::to_string(row) + " of " +
                                 std::to_string(count) + " particle rows");
        splitBlanks(line, w);
        if (w.size() != width)
            throw InputError(path, InputError::Where::Line, cursor.line,
                             "expected " + std::to_string(width) +
                                 " values (as Properties= says), found " +
                                 std::to_string(w.size()));
        auto real = [&](std::size_t c, const std::string& name) {
            double v = 0;
            const auto r = fast_float::from_chars(w[c].data(), w[c].data() + w[c].size(), v);
            if (r.ec != std::errc() || r.ptr != w[c].data() + w[c].size() || !std::isfinite(v))
                throw InputError(path, InputError::Where::Line, cursor.line,
                                 "column " + std::to_string(c + 1) + " ('" + name +
                                     "'): expected a finite number, found " + quoteForError(w[c]));
            return v;
        };
        auto integer = [&](std::size_t c, const std::string& name) {
            std::int64_t v = 0;
            const auto [end, ec] = std::from_chars(w[c].data(), w[c].data() + w[c].size(), v);
            if (ec != std::errc() || end != w[c].data() + w[c].size())
                throw InputError(path, InputError::Where::Line, cursor.line,
                                 "column " + std::to_string(c + 1) + " ('" + name +
                                     "'): expected an integer, found " + quoteForError(w[c]));
            return v;
        };
        frame.x[row] = static_cast<float>(real(posProp->first, "pos"));
        frame.y[row] = static_cast<float>(real(posProp->first + 1, "pos"));
        frame.z[row] = static_cast<float>(real(posProp->first + 2, "pos"));
        frame.ids[row] = idProp ? integer(idProp->first, idProp->name) : std::int64_t(row);
        if (radiusProp) {
            const double r = real(radiusProp->first, radiusProp->name) * (diameter ? 0.5 : 1.0);
            if (!(r > 0))
                throw InputError(path, InputError::Where::Line, cursor.line,
                                 "column '" + radiusProp->name + "' must be positive, found " +
                                     quoteForError(w[radiusProp->first]));
            frame.radius[row] = static_cast<float>(r);
        }
        for (Attr& a : attrs) {
            const std::string_view v = w[a.column];
            switch (a.type) {
            case 'R':
                a.data.floats[row] = static_cast<float>(real(a.column, a.data.name));
                break;
            case 'I': {
                const std::int64_t i = integer(a.column, a.data.name);
                if (i < INT32_MIN || i > INT32_MAX)
                    throw InputError(path, InputError::Where::Line, cursor.line,
                                     "column '" + a.data.name + "': " + quoteForError(v) +
                                         " does not fit a 32-bit integer");
                a.data.ints[row] = static_cast<std::int32_t>(i);
                break;
            }
            case 'L':
                if (v != "T" && v != "F" && v != "True" && v != "False" && v != "1" && v != "0")
                    throw InputError(path, InputError::Where::Line, cursor.line,
                                     "column '" + a.data.name + "': expected T or F, found " +
                                         quoteForError(v));
                a.data.ints[row] = (v == "T" || v == "True" || v == "1") ? 1 : 0;
                break;
            default: { // S: the name's code, in order of first appearance
                auto it = a.names.find(v);
                if (it == a.names.end()) {
                    if (a.names.size() >= 65536)
                        throw InputError(path, InputError::Where::Line, cursor.line,
                                         "column '" + a.data.name + "': more than 65536 names");
                    it = a.names.emplace(std::string(v), int(a.names.size()) + 1).first;
                }
                a.data.ints[row] = it->second;
            }
            }
        }
    }
    for (Attr& a : attrs)
        frame.attributes.push_back(std::move(a.data));
    if (auto it = pairs.find("Lattice"); it != pairs.end()) {
        std::vector<std::string_view> v;
        splitBlanks(it->second, v);
        double m[9];
        bool ok = v.size() == 9;
        for (std::size_t k = 0; ok && k < 9; ++k) {
            const auto r = fast_float::from_chars(v[k].data(), v[k].data() + v[k].size(), m[k]);
            ok = r.ec == std::errc() && std::isfinite(m[k]);
        }
        // An orthogonal cell becomes the box (origin from "Origin=", else 0).
        if (ok && m[1] == 0 && m[2] == 0 && m[3] == 0 && m[5] == 0 && m[6] == 0 && m[7] == 0) {
            double o[3] = {0, 0, 0};
            if (auto oi = pairs.find("Origin"); oi != pairs.end()) {
                std::vector<std::string_view> ov;
                splitBlanks(oi->second, ov);
                for (std::size_t k = 0; k < 3 && ov.size() == 3; ++k)
                    fast_float::from_chars(ov[k].data(), ov[k].data() + ov[k].size(), o[k]);
            }
            for (int a = 0; a < 3; ++a) {
                frame.box.lo[a] = o[a];
                frame.box.hi[a] = o[a] + m[4 * a];
            }
            frame.box.known = true;
            if (auto pbc = pairs.find("pbc"); pbc != pairs.end()) {
                std::vector<std::string_view> pv;
                splitBlanks(pbc->second, pv);
                for (std::size_t k = 0; k < 3 && pv.size() == 3; ++k)
                    frame.box.periodic[k] = pv[k] == "T" || pv[k] == "True";
            }
        }
    }
    try {
        frame.finalize();
    } catch (const std::invalid_argument& e) {
        throw InputError(path, InputError::Where::Line, commentLine, e.what());
    }
    return frame;
}

} // namespace faultline::core
