#include "ui/viewport/orbit_camera.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace faultline::ui {

namespace {
glm::dvec3 target(const core::CameraState& c) { return {c.target[0], c.target[1], c.target[2]}; }
} // namespace

CameraBasis cameraBasis(const core::CameraState& c) {
    const double az = glm::radians(c.azimuth), el = glm::radians(c.elevation);
    CameraBasis b;
    b.forward = glm::dvec3(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), -std::sin(el));
    b.right = glm::dvec3(std::cos(az), -std::sin(az), 0.0);
    b.up = glm::cross(b.right, b.forward);
    b.eye = target(c) - b.forward * std::max(c.distance, 1e-9);
    return b;
}

glm::dmat4 viewMatrix(const core::CameraState& c) {
    const CameraBasis b = cameraBasis(c);
    return glm::lookAt(b.eye, target(c), b.up);
}

glm::dmat4 projectionMatrix(const core::CameraState& c, double aspect, double sceneRadius) {
    const double d = std::max(c.distance, 1e-9);
    const double r = std::max(sceneRadius, 1e-9);
    const double farClip = d + 2.0 * r;
    if (c.orthographic) {
        const double h = d * std::tan(glm::radians(c.fovY) / 2.0);
        return glm::ortho(-h * aspect, h * aspect, -h, h, d - 2.0 * r, farClip);
    }
    const double nearClip = std::max(d - 2.0 * r, farClip * 1e-4);
    return glm::perspective(glm::radians(c.fovY), aspect, nearClip, farClip);
}

void orbit(core::CameraState& c, double dx, double dy) {
    c.azimuth = std::fmod(c.azimuth - dx * 0.3 + 360.0, 360.0);
    c.elevation = std::clamp(c.elevation + dy * 0.3, -89.0, 89.0);
}

void pan(core::CameraState& c, double dx, double dy, double viewHeight) {
    const CameraBasis b = cameraBasis(c);
    const double worldPerPixel =
        2.0 * c.distance * std::tan(glm::radians(c.fovY) / 2.0) / std::max(viewHeight, 1.0);
    const glm::dvec3 t = target(c) - b.right * (dx * worldPerPixel) + b.up * (dy * worldPerPixel);
    c.target = {t.x, t.y, t.z};
}

void zoom(core::CameraState& c, double factor) {
    if (factor > 0)
        c.distance = std::max(c.distance / factor, 1e-6);
}

void fit(core::CameraState& c, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
         double aspect) {
    const glm::dvec3 a(lo[0], lo[1], lo[2]), b(hi[0], hi[1], hi[2]);
    const glm::dvec3 centre = 0.5 * (a + b);
    c.target = {centre.x, centre.y, centre.z};
    aspect = std::max(aspect, 1e-3);
    const double tanY = std::tan(glm::radians(c.fovY) / 2.0), tanX = tanY * aspect;
    const CameraBasis basis = cameraBasis(c);
    // Each corner must lie inside the view: |x| <= depth tanX and |y| <= depth tanY, where depth
    // is the distance plus the corner's offset along the view direction (perspective); an
    // orthographic view shows a height of 2 d tanY whatever the depth.
    double d = 1e-6;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p =
            glm::dvec3(k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z) - centre;
        const double x = std::fabs(glm::dot(p, basis.right)), y = std::fabs(glm::dot(p, basis.up));
        const double z = glm::dot(p, basis.forward);
        if (c.orthographic)
            d = std::max({d, x / tanX, y / tanY});
        else
            d = std::max({d, x / tanX - z, y / tanY - z});
    }
    c.distance = d * 1.06;
}

void fitBesideLegend(core::CameraState& c, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, double width, double height,
                     double legendPixels) {
    height = std::max(height, 1.0);
    fit(c, lo, hi, std::max(width - legendPixels, 1.0) / height);
    const CameraBasis basis = cameraBasis(c);
    const double worldPerPixel = 2.0 * c.distance * std::tan(glm::radians(c.fovY) / 2.0) / height;
    for (int k = 0; k < 3; ++k)
        c.target[k] += basis.right[k] * 0.5 * legendPixels * worldPerPixel;
}

void applyPreset(core::CameraState& c, const char* preset) {
    if (!std::strcmp(preset, "top"))
        c.azimuth = 0, c.elevation = 89;
    else if (!std::strcmp(preset, "front"))
        c.azimuth = 0, c.elevation = 0;
    else if (!std::strcmp(preset, "side"))
        c.azimuth = 270, c.elevation = 0;
    else
        c.azimuth = 30, c.elevation = 25;
}

std::optional<glm::dvec2> projectToPixels(const glm::dmat4& viewProj, const glm::dvec3& p,
                                          glm::dvec2 size) {
    const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
    if (clip.w <= 1e-12)
        return std::nullopt;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return glm::dvec2((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y);
}

} // namespace faultline::ui
