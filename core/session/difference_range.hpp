// The colour range of a view's difference colouring over many frames (issue 41): a movie or a
// series of figures coloured by "change since frame 20" shares one legend, and a change is
// symmetric about zero, so zero change is always the map's middle colour.
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

} // namespace faultline::core
