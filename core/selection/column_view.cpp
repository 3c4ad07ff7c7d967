#include "core/selection/column_view.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

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

std::optional<VariableRange> variableRange(const Frame& frame, std::string_view variable) {
    if (const AttributeColumn* c = frame.attribute(variable))
        return c->min <= c->max ? std::optional(VariableRange{c->min, c->max}) : std::nullopt;
    for (int a = 0; a < 3; ++a)
        if (frame.size() > 0 && variable == std::string_view(a == 0 ? "x" : a == 1 ? "y" : "z"))
            return VariableRange{frame.centreMin()[a], frame.centreMax()[a]};
    // Kept with the frame: views ask for it every UI frame.
    if (variable == "radius" && frame.size() > 0) {
        const auto& r = frame.radiusRange();
        return r[0] <= r[1] ? std::optional(VariableRange{r[0], r[1]}) : std::nullopt;
    }
    return std::nullopt; // no such column, or an empty frame
}

std::vector<std::string> variableNamesOf(const Frame& frame) {
    std::vector<std::string> names = frame.attributeNames();
    for (const char* b : {"x", "y", "z", "radius"})
        if (std::find(names.begin(), names.end(), b) == names.end())
            names.emplace_back(b);
    return names;
}

namespace {

std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] =
                std::min({row[j] + 1, row[j - 1] + 1,
                          diagonal + (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                              std::tolower(static_cast<unsigned char>(b[j - 1]))
                                          ? 0
                                          : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

} // namespace

std::string missingVariableNote(const Frame& frame, std::string_view variable) {
    if (findColumn(frame, variable))
        return {};
    std::string note = "no variable '" + std::string(variable) + "' in this data";
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(2, variable.size() / 3) + 1;
    for (const auto& name : variableNamesOf(frame))
        if (const std::size_t d = editDistance(variable, name); d < bestDistance)
            best = name, bestDistance = d;
    return note + (best.empty() ? "" : "; did you mean '" + best + "'?");
}

} // namespace faultline::core
