// A fault's surface settings as JSON: the fields of surface.set / surface.build, of a session's
// surfaces[] and of the "surface" a fault.restore brings back. The fault they belong to is the
// caller's key ("fault"), not one of the fields.
#pragma once

#include "core/session/items/item_reader.hpp"
#include "core/session/session_state.hpp"

namespace faultline::core::items {

// kernel, voxel, iso, visible, opacity, color_by, map, range, color_reach, initial_color, color.
Json toJson(const SurfaceSettings& settings);
// Reads the fields present; "range", "color_reach", "initial_color" and "color" may be null
// (none).
void patch(SurfaceSettings& settings, const ItemReader& fields);
// The fields, in the table they are declared in once (what surface.set and surface.build accept
// besides "fault").
std::vector<std::string> surfaceFieldNames();
// voxel >= 0, iso > 0, opacity in [0, 1], a colour map, low < high, reach >= 0, colours in
// [0, 1].
void validate(const SurfaceSettings& settings);

} // namespace faultline::core::items
