#include "core/session/items/camera_codec.hpp"

namespace faultline::core::items {

Json toJson(const CameraState& c) {
    return {{"target", c.target},       {"distance", c.distance}, {"azimuth", c.azimuth},
            {"elevation", c.elevation}, {"fov_y", c.fovY},        {"orthographic", c.orthographic}};
}

void patch(CameraState& c, const ItemReader& f) {
    f.read("target", c.target);
    f.read("distance", c.distance);
    f.read("azimuth", c.azimuth);
    f.read("elevation", c.elevation);
    f.read("fov_y", c.fovY);
    f.read("orthographic", c.orthographic);
}

void validate(const CameraState& c, const std::string& prefix) {
    if (c.distance < 0)
        breaks(prefix + "distance", "must be >= 0");
    if (c.elevation < -90 || c.elevation > 90)
        breaks(prefix + "elevation", "must lie in [-90, 90]");
    if (c.fovY <= 0 || c.fovY >= 180)
        breaks(prefix + "fov_y", "must lie in (0, 180)");
}

} // namespace faultline::core::items
