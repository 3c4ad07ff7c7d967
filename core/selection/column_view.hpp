// ColumnView: a read-only view of one numeric per-sphere column of a Frame, found by name.
// Thresholds and histograms use it so attributes and the built-in x, y, z, radius work alike.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct ColumnView {
    std::string_view name;
    ColumnType type = ColumnType::Float32;
    const float* floats = nullptr;      // set when type is Float32
    const std::int32_t* ints = nullptr; // set when type is Int32
    std::size_t size = 0;

    bool isInteger() const { return type == ColumnType::Int32; }
    double value(std::size_t row) const {
        return type == ColumnType::Float32 ? static_cast<double>(floats[row])
                                           : static_cast<double>(ints[row]);
    }
};

ColumnView viewOf(const AttributeColumn& column);

// An attribute column by name; failing that the built-in "x", "y", "z" or "radius" columns.
// nullopt when the frame has no such variable.
std::optional<ColumnView> findColumn(const Frame& frame, std::string_view variable);

// The smallest and largest finite value of a variable (an attribute's cached range; the centres'
// bounds for x, y, z); nullopt when the frame has no such variable or no finite value.
struct VariableRange {
    double low = 0, high = 0;
};
std::optional<VariableRange> variableRange(const Frame& frame, std::string_view variable);

// Every variable name a frame answers to: its attributes, then x, y, z and radius.
std::vector<std::string> variableNamesOf(const Frame& frame);
// "no variable 'strian' in this data; did you mean 'strain'?" (the suggestion when a name is
// a few edits away); empty when the frame has the variable.
std::string missingVariableNote(const Frame& frame, std::string_view variable);

} // namespace faultline::core
