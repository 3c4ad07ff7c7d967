// The viewport's orbit camera on the session's CameraState: matrices, turntable orbit, pan,
// zoom and fit. Azimuth is the compass bearing the camera looks along (0: looking north, east
// to the right), elevation how far it looks down from the horizontal; +z stays up on screen.
#pragma once

#include "core/session/session_state.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <optional>

namespace faultline::ui {

struct CameraBasis {
    glm::dvec3 eye, forward, right, up;
};

CameraBasis cameraBasis(const core::CameraState& camera);
glm::dmat4 viewMatrix(const core::CameraState& camera);
// Clip planes enclose a sphere of `sceneRadius` around the target.
glm::dmat4 projectionMatrix(const core::CameraState& camera, double aspect, double sceneRadius);

// Turntable: drag right turns the model right (the bearing turns left), drag up tilts it.
void orbit(core::CameraState& camera, double dxPixels, double dyPixels);
// Moves the target so the model follows the cursor; `viewHeight` in pixels.
void pan(core::CameraState& camera, double dxPixels, double dyPixels, double viewHeight);
// factor > 1 moves closer.
void zoom(core::CameraState& camera, double factor);
// Centres the box [lo, hi] and sets the distance so all of it shows in a view of `aspect`
// (width / height) with a small margin; keeps the direction.
void fit(core::CameraState& camera, const std::array<double, 3>& lo,
         const std::array<double, 3>& hi, double aspect);
// fit() into a width x height view whose right `legendPixels` belong to a colour legend: the
// box is centred in the rest.
void fitBesideLegend(core::CameraState& camera, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, double width, double height,
                     double legendPixels);
// Standard directions: "top" "front" (from the south) "side" (from the east) "iso".
void applyPreset(core::CameraState& camera, const char* preset);

// A world point in pixels of a viewport of `size` (origin top left); nullopt behind the eye.
std::optional<glm::dvec2> projectToPixels(const glm::dmat4& viewProj, const glm::dvec3& p,
                                          glm::dvec2 size);

} // namespace faultline::ui
