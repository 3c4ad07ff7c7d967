// Difference colouring: how a variable changed, and how far each sphere moved, since a reference
// frame, matched by particle id, as float columns the renderer colours by like any other.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace faultline::core {

// Per row of `now`: value_now - value_in_reference for the same particle id; NaN where the id is
// not in `reference` or `reference` lacks the variable. `variable` is an attribute name, or x, y,
// z or radius. Named "<variable> change". Throws std::invalid_argument when `now` lacks it.
AttributeColumn variableChange(const Frame& now, const Frame& reference, std::string_view variable);

// Per row of `now`: |pos_now - pos_in_reference| for the same particle id; NaN where the id is
// not in `reference`. Along a periodic axis of the reference box the shortest image counts
// (triclinic cells too), so a sphere that crossed the boundary moved a little, not a box length.
// Named "displacement".
AttributeColumn displacementSince(const Frame& now, const Frame& reference);

// Caches a float column's min and max (NaN ignored; 0 and 0 when every value is NaN), in
// parallel, as Frame::finalize does for a file's columns.
void cacheColumnRange(AttributeColumn& column);

// The finite values' min and max of `variable` (an attribute, or x, y, z or radius) over the rows
// whose `mask` byte is non-zero, in parallel: a view's "this frame" colour range counts only
// the spheres it shows (issue 41). Nothing when the frame lacks the variable, `mask` does not
// have a byte per row, or no such row has a finite value.
std::optional<std::pair<double, double>> maskedRange(const Frame& frame, std::string_view variable,
                                                     const std::vector<std::uint8_t>& mask);

// The `low` and `high` quantiles (fractions, 0 <= low < high <= 1; core::quantile, interpolated)
// of the finite values of `variable` over the rows whose `mask` byte is non-zero: a colour range
// that a few extreme values (grains thrown out of a model, a free surface's strain) do not wash
// out. Nothing under the same conditions as maskedRange.
std::optional<std::pair<double, double>> maskedQuantiles(const Frame& frame,
                                                         std::string_view variable,
                                                         const std::vector<std::uint8_t>& mask,
                                                         double low, double high);

} // namespace faultline::core
