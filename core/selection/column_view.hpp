// ColumnView: a read-only view of one numeric per-sphere column of a Frame, found by name.
// Thresholds and histograms use it so attributes and the built-in x, y, z, radius work alike.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string_view>

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

} // namespace faultline::core
