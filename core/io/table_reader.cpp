#include "core/io/table_reader.hpp"

#include "core/io/input_error.hpp"
#include "core/io/numeric_table.hpp"
#include "core/io/parsed_columns.hpp"
#include "core/util/ascii.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace faultline::core {

namespace {

std::vector<std::string> headerNames(std::string_view line, char separator) {
    std::vector<std::string> names;
    std::size_t i = 0;
    auto isSep = [&](char c) { return separator ? c == separator : (c == ' ' || c == '\t'); };
    while (i <= line.size()) {
        std::size_t j = i;
        while (j < line.size() && !isSep(line[j]))
            ++j;
        std::string_view w = line.substr(i, j - i);
        while (!w.empty() && std::isspace(static_cast<unsigned char>(w.front())))
            w.remove_prefix(1);
        while (!w.empty() && std::isspace(static_cast<unsigned char>(w.back())))
            w.remove_suffix(1);
        if (w.size() >= 2 && (w.front() == '"' || w.front() == '\'') && w.back() == w.front())
            w = w.substr(1, w.size() - 2);
        if (!w.empty() || separator)
            names.emplace_back(w);
        if (j >= line.size())
            break;
        i = j + 1;
        if (!separator)
            while (i < line.size() && isSep(line[i]))
                ++i;
    }
    return names;
}

// What a column name means when matched: lower case, units in brackets or parentheses dropped
// ("Pos.x [m]" is pos.x), blanks trimmed. The name shown stays as the file wrote it.
std::string matchKey(std::string_view name) {
    std::string out;
    int depth = 0;
    for (char c : name) {
        if (c == '[' || c == '(')
            ++depth;
        else if ((c == ']' || c == ')') && depth > 0)
            --depth;
        else if (depth == 0)
            out += c;
    }
    while (!out.empty() && std::isspace(static_cast<unsigned char>(out.back())))
        out.pop_back();
    std::size_t first = 0;
    while (first < out.size() && std::isspace(static_cast<unsigned char>(out[first])))
        ++first;
    return asciiLower(out.substr(first));
}

// The names a coordinate goes by in the programs users have: x; ParaView's Points:0 and
// coordinates:0; DualSPHysics' Pos.x (and PosDouble.x); pos_x, position_x, position:0 ...
std::vector<std::string> coordinateNames(char axis, int index) {
    const std::string a(1, axis), i = std::to_string(index);
    return {a,
            "points:" + i,
            "point:" + i,
            "coordinates:" + i,
            "coords:" + i,
            "position:" + i,
            "pos:" + i,
            "pos." + a,
            "pos_" + a,
            "pos" + a,
            "position." + a,
            "position_" + a,
            "posdouble." + a,
            "coordinates_" + i};
}

constexpr const char* kAcceptedCoordinates =
    "x y z; Points:0..2; coordinates:0..2; Pos.x/Pos.y/Pos.z; pos_x; position_x; position:0";

} // namespace

Frame parseTable(const std::string& path, std::string_view text) {
    // Header: the first non-blank line; a leading '#' is allowed.
    std::size_t pos = 0;
    std::uint64_t line = 0;
    std::string_view header;
    while (pos < text.size()) {
        const void* nl = std::memchr(text.data() + pos, '\n', text.size() - pos);
        const std::size_t end =
            nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text.data()) : text.size();
        std::string_view l = text.substr(pos, end - pos);
        pos = nl ? end + 1 : text.size();
        ++line;
        if (l.find_first_not_of(" \t\r") != std::string_view::npos) {
            header = l;
            break;
        }
    }
    if (header.empty())
        throw InputError(path, "empty file: expected a header row naming columns x, y, z");
    if (std::memchr(header.data(), '\0', header.size()))
        throw InputError(path, InputError::Where::Line, line,
                         "binary data where a header row was expected");
    while (!header.empty() && (header.front() == '#' || header.front() == ' '))
        header.remove_prefix(1);
    while (!header.empty() && std::isspace(static_cast<unsigned char>(header.back())))
        header.remove_suffix(1);
    // Delimiter: comma, then semicolon (DualSPHysics), then tab (names may hold spaces), else
    // blanks. Rows split on the comma or semicolon; tabs and blanks are both blanks in rows.
    const char separator = header.find(',') != std::string_view::npos   ? ','
                           : header.find(';') != std::string_view::npos ? ';'
                                                                        : 0;
    std::vector<std::string> names = headerNames(header, separator);
    if (!separator && header.find('\t') != std::string_view::npos) {
        // Tabs between names that hold spaces ("X [m]<tab>Y [m]"): split on tabs when that
        // gives as many names as the first row has values.
        std::vector<std::string> byTab = headerNames(header, '\t');
        std::size_t at = pos;
        std::string_view first;
        while (at < text.size() && first.empty()) {
            const std::size_t end = std::min(text.find('\n', at), text.size());
            const std::string_view l = text.substr(at, end - at);
            if (l.find_first_not_of(" \t\r") != std::string_view::npos)
                first = l;
            at = end + 1;
        }
        if (byTab.size() != names.size() && byTab.size() == headerNames(first, 0).size())
            names = std::move(byTab);
    }
    // DualSPHysics' PartCSV ends every line, the header's too, with ';': no column after it.
    if (separator && names.size() > 1 && names.back().empty() && header.back() == separator)
        names.pop_back();
    // Yade's export.text / ymport.text: "#format x_y_z_r" names the columns joined by '_'.
    if (!separator && names.size() == 2 && asciiLower(names[0]) == "format") {
        const std::string spec = names[1];
        names.clear();
        for (std::size_t i = 0; i <= spec.size();) {
            const std::size_t j = std::min(spec.find('_', i), spec.size());
            names.push_back(spec.substr(i, j - i));
            i = j + 1;
        }
        // export.textExt(..., format='x_y_z_r_attrs', attrs=[...]) writes each attribute's
        // values (a vector's three) after the radius, unnamed: attr_1 .. attr_n, n from the
        // first row. Its `comment` comes as '#' lines after the format line: one naming as
        // many columns as the rows hold names them.
        std::vector<std::string> commentNames;
        while (pos < text.size()) {
            const std::size_t end = std::min(text.find('\n', pos), text.size());
            std::string_view l = text.substr(pos, end - pos);
            const std::size_t first = l.find_first_not_of(" \t\r");
            if (first != std::string_view::npos && l[first] != '#')
                break; // the first row
            if (first != std::string_view::npos && commentNames.empty()) {
                l.remove_prefix(first + 1);
                commentNames = headerNames(l, 0);
            }
            pos = std::min(end + 1, text.size()); // a last line without a newline ends it
            ++line;
        }
        if (!names.empty() && asciiLower(names.back()) == "attrs") {
            names.pop_back();
            const std::size_t end = std::min(text.find('\n', pos), text.size());
            const std::size_t values = headerNames(text.substr(pos, end - pos), 0).size();
            if (commentNames.size() == values && values > names.size()) {
                for (std::size_t k = names.size(); k < values; ++k)
                    names.push_back(commentNames[k]);
            } else {
                for (std::size_t k = 1; names.size() < values; ++k)
                    names.push_back("attr_" + std::to_string(k));
            }
        }
    }
    const std::uint64_t headerLine = line;

    std::vector<std::string> keys;
    for (const auto& n : names)
        keys.push_back(matchKey(n));
    auto find = [&](const std::vector<std::string>& wanted) -> int {
        for (const auto& w : wanted)
            for (std::size_t c = 0; c < keys.size(); ++c)
                if (keys[c] == w)
                    return static_cast<int>(c);
        return -1;
    };
    const int xc = find(coordinateNames('x', 0)), yc = find(coordinateNames('y', 1)),
              zc = find(coordinateNames('z', 2));
    if (xc < 0 || yc < 0 || zc < 0) {
        std::string seen;
        for (const auto& n : names)
            seen += (seen.empty() ? "" : ", ") + n;
        throw InputError(
            path, InputError::Where::Line, headerLine,
            "header must name columns x, y and z (accepted: " + std::string(kAcceptedCoordinates) +
                "; units in brackets are ignored), found " + quoteForError(seen, 120));
    }
    const int idc = find({"id", "particle_id", "pid", "idp", "ids", "particleid", "particle id"});
    const int rc = find({"radius", "r", "rad"});
    const int dc = rc < 0 ? find({"diameter", "diam", "d"}) : -1;
    for (std::size_t c = 0; c < names.size(); ++c) {
        if (names[c].empty())
            throw InputError(path, InputError::Where::Line, headerLine,
                             "column " + std::to_string(c + 1) + " has no name");
        for (std::size_t k = 0; k < c; ++k)
            if (names[k] == names[c])
                throw InputError(path, InputError::Where::Line, headerLine,
                                 "column '" + names[c] + "' appears twice");
    }

    // Body: everything after the header, less trailing blank lines.
    std::size_t bodyEnd = text.size();
    while (bodyEnd > pos && std::isspace(static_cast<unsigned char>(text[bodyEnd - 1])))
        --bodyEnd;
    std::string_view body = text.substr(pos, bodyEnd - pos);
    const std::size_t rows =
        body.empty() ? 0 : static_cast<std::size_t>(std::count(body.begin(), body.end(), '\n')) + 1;

    Frame frame;
    resizeColumnsInParallel({&frame.x, &frame.y, &frame.z, &frame.radius}, {&frame.ids}, rows);
    std::vector<TableColumnTarget> targets(names.size());
    std::vector<std::vector<float>> values(names.size());
    std::vector<bool> isAttribute(names.size(), false);
    for (std::size_t c = 0; c < names.size(); ++c) {
        const int ci = static_cast<int>(c);
        TableColumnTarget& t = targets[c];
        t.name = names[c];
        t.kind = TableColumnTarget::Kind::Float;
        if (ci == idc) {
            t.kind = TableColumnTarget::Kind::Int64;
            t.ints = frame.ids.data();
        } else if (ci == xc || ci == yc || ci == zc) {
            t.floats = (ci == xc ? frame.x : ci == yc ? frame.y : frame.z).data();
            t.requireFinite = true;
        } else if (ci == rc || ci == dc) {
            t.floats = frame.radius.data();
            t.requireFinite = true;
        } else {
            values[c].resize(rows);
            t.floats = values[c].data();
            isAttribute[c] = true;
        }
    }
    NumericTableSpec spec;
    spec.path = path;
    spec.firstLine = headerLine + 1;
    spec.rows = rows;
    spec.separator = separator;
    parseNumericTable(body, layoutNumericTable(body, spec), spec, targets);

    completeParsedFrame(frame,
                        {names, targets, values, isAttribute, idc >= 0,
                         rc >= 0   ? ParsedColumns::Radius::Radius
                         : dc >= 0 ? ParsedColumns::Radius::Diameter
                                   : ParsedColumns::Radius::Missing},
                        path, headerLine);
    return frame;
}

} // namespace faultline::core
