// Colouring by category: each sphere in the colour of the fault that holds it (the view variable
// "faults"), or of the candidate it would join (the Faults panel's preview). Values are k + 0.5
// for category k (0: none), drawn with a palette colour map over [0, palette size].
#pragma once

#include "core/faults/fault.hpp"
#include "core/model/frame.hpp"
#include "ui/render/legend_layout.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::ui {

// The colour variable that colours spheres by their fault.
inline constexpr const char* kFaultsVariable = "faults";
// Spheres in no category: a light neutral grey, so coloured ones stand out.
inline constexpr glm::vec3 kUncategorised{0.78f, 0.78f, 0.76f};

struct CategoryColoring {
    std::shared_ptr<const core::AttributeColumn> values; // one per row of the frame
    std::vector<glm::vec3> palette;                      // [0]: uncategorised
    std::vector<std::string> names;                      // one per palette colour
};

// The legend of a categories colouring: its named colours, "no fault" (uncategorised) last.
std::vector<LegendEntry> legendEntries(const CategoryColoring& coloring);

// Members of faults in their fault's colour (the first fault listed wins).
CategoryColoring faultColoring(const core::Frame& frame, std::span<const core::Fault> faults);
// Rows labelled 0..count-1 (-1: none) in the candidates' colours (core::candidateColor).
// Named prefix + "1".."count", as fault.candidates would name them.
CategoryColoring candidateColoring(std::span<const std::int32_t> rowLabel, std::size_t count,
                                   std::string_view prefix = "C");
// Changes when anything faultColoring depends on changes (members, colours, order).
std::uint64_t faultColoringKey(std::span<const core::Fault> faults);

} // namespace faultline::ui
