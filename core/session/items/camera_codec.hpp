// A view's camera as JSON: the fields of camera.set and of a session's views[].camera.
#pragma once

#include "core/session/items/item_reader.hpp"
#include "core/session/session_state.hpp"

namespace faultline::core::items {

Json toJson(const CameraState& camera);
// Reads the fields present (target, distance, azimuth, elevation, fov_y, orthographic).
void patch(CameraState& camera, const ItemReader& fields);
// The fields, in the table they are declared in once (what camera.set accepts besides "view").
std::vector<std::string> cameraFieldNames();
// distance >= 0, elevation in [-90, 90], fov_y in (0, 180); `prefix` is the camera's path.
void validate(const CameraState& camera, const std::string& prefix = {});

} // namespace faultline::core::items
