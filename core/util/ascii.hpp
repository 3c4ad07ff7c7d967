// Small text helpers for names in user files and settings: ASCII-only case folding, since column
// names, keywords and option values are ASCII and locale-dependent folding would surprise; and
// the readers' blank trimming and word splitting.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

inline std::string asciiLower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z')
            c = static_cast<char>(c - 'A' + 'a');
    return out;
}

// Without leading and trailing blanks (space, tab, carriage return).
inline std::string_view trimBlanks(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

// The words of a line, split on blanks (space, tab, carriage return), into `out` (cleared).
inline void splitBlanks(std::string_view line, std::vector<std::string_view>& out) {
    out.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
            ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
            ++i;
        if (i > start)
            out.push_back(line.substr(start, i - start));
    }
}

} // namespace faultline::core
