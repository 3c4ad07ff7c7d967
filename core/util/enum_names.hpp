// Enum <-> name tables: each enum that has names in journals, sessions, CSV or the UI lists them
// once, in one table beside the enum's functions, and both directions come from it.
//     constexpr EnumName<BoxMode> kBoxModes[] = {{BoxMode::Keep, "keep"}, {BoxMode::Cut, "cut"}};
//     nameIn(kBoxModes, mode); valueIn(kBoxModes, text); namesIn(kBoxModes) == "keep | cut"
// A value's first entry is its name; later entries for the same value are aliases accepted
// when parsing ("ortho" for orthographic).
#pragma once

#include "core/util/ascii.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

template <typename E> struct EnumName {
    E value;
    std::string_view name;
};

// The name of `value`, or `absent` when the table lacks it (an out-of-range cast).
template <typename E, std::size_t N>
constexpr std::string_view nameIn(const EnumName<E> (&table)[N], E value,
                                  std::string_view absent = "?") {
    for (const EnumName<E>& e : table)
        if (e.value == value)
            return e.name;
    return absent;
}

enum class NameCase { Exact, Ignore };

// The value named `name` (a name or an alias); nullopt when none is. NameCase::Ignore compares
// ASCII letters without case.
template <typename E, std::size_t N>
std::optional<E> valueIn(const EnumName<E> (&table)[N], std::string_view name,
                         NameCase nameCase = NameCase::Exact) {
    const std::string folded = nameCase == NameCase::Ignore ? asciiLower(name) : std::string(name);
    for (const EnumName<E>& e : table)
        if (e.name == folded)
            return e.value;
    return std::nullopt;
}

// The names (no aliases) joined by `separator`, the last two by `lastSeparator` (default: the
// same), for messages: "keep | cut"; namesIn(t, ", ", " or ") == "all, labelled or only".
template <typename E, std::size_t N>
std::string namesIn(const EnumName<E> (&table)[N], std::string_view separator = " | ",
                    std::optional<std::string_view> lastSeparator = std::nullopt) {
    std::vector<std::string_view> names;
    for (std::size_t i = 0; i < N; ++i) {
        bool alias = false;
        for (std::size_t j = 0; j < i && !alias; ++j)
            alias = table[j].value == table[i].value;
        if (!alias)
            names.push_back(table[i].name);
    }
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0)
            out += i + 1 == names.size() ? lastSeparator.value_or(separator) : separator;
        out += names[i];
    }
    return out;
}

} // namespace faultline::core
