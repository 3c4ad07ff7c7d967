#include "core/selection/column_view.hpp"

namespace faultline::core {

ColumnView viewOf(const AttributeColumn& column) {
    ColumnView view;
    view.name = column.name;
    view.type = column.type;
    view.size = column.size();
    if (column.type == ColumnType::Float32)
        view.floats = column.floats.data();
    else
        view.ints = column.ints.data();
    return view;
}

std::optional<ColumnView> findColumn(const Frame& frame, std::string_view variable) {
    if (const AttributeColumn* column = frame.attribute(variable))
        return viewOf(*column);
    // Names point at literals, never at the caller's string.
    const std::vector<float>* builtin = nullptr;
    std::string_view name;
    if (variable == "x")
        builtin = &frame.x, name = "x";
    else if (variable == "y")
        builtin = &frame.y, name = "y";
    else if (variable == "z")
        builtin = &frame.z, name = "z";
    else if (variable == "radius")
        builtin = &frame.radius, name = "radius";
    if (!builtin)
        return std::nullopt;
    ColumnView view;
    view.name = name;
    view.type = ColumnType::Float32;
    view.floats = builtin->data();
    view.size = builtin->size();
    return view;
}

} // namespace faultline::core
