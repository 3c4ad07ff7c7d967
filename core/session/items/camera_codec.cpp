#include "core/session/items/camera_codec.hpp"

namespace faultline::core::items {

namespace {
// Each field once: its JSON and how it is read.
template <auto Member> void readInto(CameraState& c, const ItemReader& f, const char* name) {
    f.read(name, c.*Member);
}
const Field<CameraState> kFields[] = {
    {"target", [](const CameraState& c) { return Json(c.target); }, readInto<&CameraState::target>},
    {"distance", [](const CameraState& c) { return Json(c.distance); },
     readInto<&CameraState::distance>},
    {"azimuth", [](const CameraState& c) { return Json(c.azimuth); },
     readInto<&CameraState::azimuth>},
    {"elevation", [](const CameraState& c) { return Json(c.elevation); },
     readInto<&CameraState::elevation>},
    {"fov_y", [](const CameraState& c) { return Json(c.fovY); }, readInto<&CameraState::fovY>},
    {"orthographic", [](const CameraState& c) { return Json(c.orthographic); },
     readInto<&CameraState::orthographic>},
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
