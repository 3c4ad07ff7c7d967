// Small text helpers for names in user files and settings: ASCII-only case folding, since column
// names, keywords and option values are ASCII and locale-dependent folding would surprise.
#pragma once

#include <string>
#include <string_view>

namespace faultline::core {

inline std::string asciiLower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z')
            c = static_cast<char>(c - 'A' + 'a');
    return out;
}

} // namespace faultline::core
