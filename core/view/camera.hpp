// The viewport camera as plain, serialisable state (target, distance, orientation, lens) and the
// pure functions that move it: trackball/turntable orbit, pan, zoom to cursor, fit, presets.
#pragma once

#include "core/view/geometry.hpp"

#include <glm/ext/quaternion_double.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string_view>

namespace faultline::core {

enum class Projection { Perspective, Orthographic };

std::string_view projectionName(Projection p); // "perspective" | "orthographic"
std::optional<Projection> parseProjection(std::string_view name);

// World orientation: +x east, +y north, +z up.
enum class ViewPreset {
    Front,  // from the south looking north, z up, east to the right
    Back,   // from the north looking south
    Left,   // from the west looking east
    Side,   // from the east looking west, north to the right ("right" view)
    Top,    // from above looking down, north up, east to the right
    Bottom, // from below looking up, north up, west to the right
    Iso,    // from the south-south-west, 30 degrees above the horizon
};

std::string_view viewPresetName(ViewPreset p);
// "front" "back" "left" "side" (or "right") "top" "bottom" "iso"; case-insensitive.
std::optional<ViewPreset> parseViewPreset(std::string_view name);

// Everything a view's camera is. Plain fields, so a session can store and restore it.
// The eye sits `distance` from `target` along the camera's +z axis; the camera looks along its
// -z axis with +y up (OpenGL convention). Orthographic views show a height of
// 2 * distance * tan(fovY / 2) at the target, so switching projection keeps the scale there.
struct Camera {
    glm::dvec3 target{0.0};
    double distance = 10.0;
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0}; // camera-to-world rotation (w, x, y, z)
    double fovYDegrees = 30.0;
    Projection projection = Projection::Perspective;

    bool operator==(const Camera&) const = default;

    glm::dvec3 eye() const;
    glm::dvec3 forward() const; // unit, towards the target
    glm::dvec3 up() const;
    glm::dvec3 right() const;
    double viewHeightAtTarget() const;
};

struct ClipRange {
    double nearClip = 0.1;
    double farClip = 100.0;
};

glm::dmat4 viewMatrix(const Camera& camera);
glm::dmat4 projectionMatrix(const Camera& camera, double aspect, ClipRange clip);
// Near and far planes enclosing `scene` (with a margin); the near plane stays in front of the eye
// for perspective views and may go behind it for orthographic ones.
ClipRange clipRangeFor(const Camera& camera, const BoundingSphere& scene);

// The ray through a point in normalized device coordinates (x, y in [-1, 1], y up), in world
// space: from the eye for perspective, from the near side of the view for orthographic.
Ray cameraRay(const Camera& camera, glm::dvec2 ndc, double aspect);

// Virtual trackball: the scene turns as if the cursor dragged a ball from `fromNdc` to `toNdc`
// around the target. `aspect` (width / height) keeps the ball round on a wide viewport.
void orbitTrackball(Camera& camera, glm::dvec2 fromNdc, glm::dvec2 toNdc, double aspect);
// Turntable: yaw about the world z axis through the target, then pitch about the camera's right
// axis; the pitch stops short of looking straight up or down so z stays up on screen.
void orbitTurntable(Camera& camera, double yawRadians, double pitchRadians);
// Moves target and eye so the scene follows the cursor by `deltaNdc`.
void pan(Camera& camera, glm::dvec2 deltaNdc, double aspect);
// Zooms by `factor` (> 1 moves closer) keeping the point under `cursorNdc` (on the plane through
// the target facing the camera) fixed on screen.
void zoomToCursor(Camera& camera, double factor, glm::dvec2 cursorNdc, double aspect);
// Centres `sphere` and sets the distance so it fills the view with `margin` (1 = touching).
void fitSphere(Camera& camera, const BoundingSphere& sphere, double aspect, double margin = 1.08);
// Centres the box and sets the distance so all its corners are in view with `margin`: tighter
// than fitSphere for the flat blocks DEM models are. Keeps the orientation.
void fitBox(Camera& camera, const Aabb& box, double aspect, double margin = 1.05);
// Turns the camera to a preset direction, keeping its target and distance.
void applyPreset(Camera& camera, ViewPreset preset);
// Camera-to-world rotation looking along `forward` with `up` roughly up on screen.
glm::dquat lookRotation(const glm::dvec3& forward, const glm::dvec3& up);

} // namespace faultline::core
