#include "ui/viewport/category_colors.hpp"

#include "core/faults/candidates.hpp"

#include <algorithm>
#include <bit>
#include <functional>

namespace faultline::ui {

namespace {

std::shared_ptr<core::AttributeColumn> emptyColumn(const char* name, std::size_t rows) {
    auto c = std::make_shared<core::AttributeColumn>();
    c->name = name;
    c->type = core::ColumnType::Float32;
    c->floats.assign(rows, 0.5f);
    return c;
}

void finish(core::AttributeColumn& c, std::size_t categories) {
    c.min = 0.0;
    c.max = static_cast<double>(categories);
}

} // namespace

CategoryColoring faultColoring(const core::Frame& frame, std::span<const core::Fault> faults) {
    CategoryColoring out;
    auto column = emptyColumn(kFaultsVariable, frame.size());
    out.palette.push_back(kUncategorised);
    out.names.push_back("no fault");
    // Later faults first, so the first fault listed paints last and wins.
    for (std::size_t k = faults.size(); k-- > 0;)
        for (std::int64_t id : faults[k].ids)
            if (auto row = frame.rowOf(id))
                column->floats[*row] = static_cast<float>(k + 1) + 0.5f;
    for (const auto& f : faults) {
        out.palette.push_back(glm::vec3(f.color[0], f.color[1], f.color[2]));
        out.names.push_back(f.name);
    }
    finish(*column, out.palette.size());
    out.values = std::move(column);
    return out;
}

CategoryColoring candidateColoring(std::span<const std::int32_t> rowLabel, std::size_t count,
                                   std::string_view prefix) {
    CategoryColoring out;
    auto column = emptyColumn("candidates", rowLabel.size());
    for (std::size_t i = 0; i < rowLabel.size(); ++i)
        if (rowLabel[i] >= 0 && static_cast<std::size_t>(rowLabel[i]) < count)
            column->floats[i] = static_cast<float>(rowLabel[i] + 1) + 0.5f;
    out.palette.push_back(kUncategorised);
    out.names.push_back("no candidate");
    for (std::size_t k = 0; k < count; ++k) {
        const auto c = core::candidateColor(k);
        out.palette.push_back(glm::vec3(c[0], c[1], c[2]));
        out.names.push_back(std::string(prefix) + std::to_string(k + 1));
    }
    finish(*column, out.palette.size());
    out.values = std::move(column);
    return out;
}

std::vector<LegendEntry> legendEntries(const CategoryColoring& coloring) {
    std::vector<LegendEntry> out;
    const std::size_t n = std::min(coloring.palette.size(), coloring.names.size());
    for (std::size_t k = 1; k < n; ++k)
        out.push_back({coloring.names[k], coloring.palette[k]});
    if (n > 0)
        out.push_back({coloring.names[0], coloring.palette[0]});
    return out;
}

std::uint64_t faultColoringKey(std::span<const core::Fault> faults) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    auto mix = [&h](std::uint64_t v) { h = (h ^ v) * 0x100000001b3ull; };
    for (const auto& f : faults) {
        mix(std::hash<std::string>{}(f.name));
        for (float c : f.color)
            mix(std::bit_cast<std::uint32_t>(c));
        mix(core::hashMemberIds(f.ids));
    }
    return h;
}

} // namespace faultline::ui
