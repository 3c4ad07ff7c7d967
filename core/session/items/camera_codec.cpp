#include "core/session/items/camera_codec.hpp"

namespace faultline::core::items {

namespace {
// Each field once: its JSON and how it is read.
using C = CameraState;
const Field<C> kFields[] = {
    member<C, &C::target>("target"),   member<C, &C::distance>("distance"),
    member<C, &C::azimuth>("azimuth"), member<C, &C::elevation>("elevation"),
    member<C, &C::fovY>("fov_y"),      member<C, &C::orthographic>("orthographic"),
};
} // namespace

Json toJson(const CameraState& c) { return fieldsToJson(c, kFields); }

void patch(CameraState& c, const ItemReader& f) { patchFields(c, f, kFields); }

std::vector<std::string> cameraFieldNames() { return fieldNames(kFields); }

void validate(const CameraState& c, const std::string& prefix) {
    if (c.distance < 0)
        breaks(prefix + "distance", "must be >= 0");
    if (c.elevation < -90 || c.elevation > 90)
        breaks(prefix + "elevation", "must lie in [-90, 90]");
    if (c.fovY <= 0 || c.fovY >= 180)
        breaks(prefix + "fov_y", "must lie in (0, 180)");
}

} // namespace faultline::core::items
