// The colour range of a view over many frames, so a movie or a series of figures shares one
// legend (issue 41: a movie coloured by "change since frame 20" took each frame's own range);
// a change is symmetric about zero, so zero change is always the map's middle colour.
#pragma once

#include "core/color/colormap.hpp"
#include "core/data/dataset.hpp"
#include "core/session/session_state.hpp"

#include <optional>
#include <vector>

namespace faultline::core {

// A change range made symmetric about zero: [-m, m] with m the larger of |low| and |high|.
ValueRange symmetricAboutZero(ValueRange range);

// The range of the view's difference column (change: symmetric about zero; displacement: from
// 0) over `frames` (every frame when empty), each against its own reference; nothing when the
// view colours by no difference or no frame has a value.
std::optional<ValueRange> differenceRangeOverFrames(const Dataset& dataset, const ViewState& view,
                                                    std::vector<std::size_t> frames = {});

// What a view's colours span over `frames` (every frame when empty): its difference column's
// range as above, else its variable's (x, y, z too) over those frames (a view whose range mode is
// "percentile": from the lowest frame's 1st percentile to the highest frame's 99th, so a movie's
// frames share colours that a few extremes do not wash out); nothing without a variable or a
// value.
std::optional<ValueRange> colorRangeOverFrames(const Dataset& dataset, const ViewState& view,
                                               const std::vector<std::size_t>& frames = {});

} // namespace faultline::core
