// A view as JSON: a session's views[] and what view.restore brings back (name, frame binding,
// colouring, camera, linked camera, context points). The flat ops that change a view (view.add,
// view.set, color.set, camera.set) read their own fields and then check the view with
// validate(), so a view no op accepts cannot come from a file either.
#pragma once

#include "core/session/items/item_reader.hpp"
#include "core/session/session_state.hpp"

namespace faultline::core::items {

Json toJson(const ViewState& view);
// Reads the fields present: name, frame {relative, value}, color {variable, map, range_mode,
// range, difference {mode, reference {relative, value}}}, camera {...}, linked_camera,
// context_points.
void patch(ViewState& view, const ItemReader& fields);
// The colouring's plain fields, as a view's "color" object and color.set both give them:
// variable, map, range_mode, range (the difference differs in shape: an object in files,
// "difference" and since_frame / since_offset in the op).
void patchColor(ViewState& view, const ItemReader& fields);
// A name; an absolute frame >= 0; a known colour map and range mode; low < high; a change
// colouring has a variable; the camera's rules (camera_codec.hpp).
void validate(const ViewState& view);

} // namespace faultline::core::items
