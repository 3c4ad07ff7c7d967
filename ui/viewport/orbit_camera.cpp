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

// The fits' margin: the box fills 1 / 1.06 of the view.
constexpr double kFitMargin = 1.06;

// The box [lo, hi] centred on the camera's target: its centre, and each corner's offset from it
// across the view (right), up and along the view (forward), for the fits below; and the basis.
struct BoxInView {
    double x[8], y[8], z[8];
    CameraBasis basis;
};
BoxInView boxInView(core::CameraState& c, const std::array<double, 3>& lo,
                    const std::array<double, 3>& hi) {
    const glm::dvec3 a(lo[0], lo[1], lo[2]), b(hi[0], hi[1], hi[2]);
    const glm::dvec3 centre = 0.5 * (a + b);
    c.target = {centre.x, centre.y, centre.z};
    BoxInView box;
    box.basis = cameraBasis(c);
    const CameraBasis& basis = box.basis;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p =
            glm::dvec3(k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z) - centre;
        box.x[k] = glm::dot(p, basis.right);
        box.y[k] = glm::dot(p, basis.up);
        box.z[k] = glm::dot(p, basis.forward);
    }
    return box;
}
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
    const BoxInView box = boxInView(c, lo, hi);
    aspect = std::max(aspect, 1e-3);
    const double tanY = std::tan(glm::radians(c.fovY) / 2.0), tanX = tanY * aspect;
    // Each corner must lie inside the view: |x| <= depth tanX and |y| <= depth tanY, where depth
    // is the distance plus the corner's offset along the view direction (perspective); an
    // orthographic view shows a height of 2 d tanY whatever the depth.
    double d = 1e-6;
    for (int k = 0; k < 8; ++k) {
        const double x = std::fabs(box.x[k]), y = std::fabs(box.y[k]), z = box.z[k];
        if (c.orthographic)
            d = std::max({d, x / tanX, y / tanY});
        else
            d = std::max({d, x / tanX - z, y / tanY - z});
    }
    c.distance = d * kFitMargin;
}

void fitBesideLegend(core::CameraState& c, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, double width, double height,
                     double legendPixels) {
    height = std::max(height, 1.0);
    width = std::max(width, 1.0);
    legendPixels = std::clamp(legendPixels, 0.0, width - 1.0);
    if (!(legendPixels > 0)) {
        fit(c, lo, hi, width / height);
        return;
    }
    // The box must show in the view's pixels left of the legend: the target moves right by s
    // (the model left). In a perspective view a corner nearer the eye moves further on screen
    // than the target's depth does, so the distance and s are found together. A corner at x
    // across the view and depth e (the distance plus its offset along the view) shows at
    // (x - s) / e, in tangents of the view's angle; the room is [-T, R] across (R short of the
    // legend) and [-tanY, tanY] up, each less the margin. For a distance d the s that keep every
    // corner in the room form a range, which widens as d grows: the least d with one. Then s
    // such that the box is centred in the room (its left gap equals its right one), found by
    // bisection: moving s moves every corner the same way. (Orthographic: e = d for every
    // corner.)
    const double tanY = std::tan(glm::radians(c.fovY) / 2.0);
    const double T = tanY * width / height, R = T * (1.0 - 2.0 * legendPixels / width);
    const double mid = 0.5 * (R - T), half = 0.5 * (R + T) / kFitMargin;
    const double roomLeft = mid - half, roomRight = mid + half, roomUp = tanY / kFitMargin;
    const BoxInView box = boxInView(c, lo, hi);
    const CameraBasis& basis = box.basis;
    const double* x = box.x;
    double y[8], z[8];
    for (int k = 0; k < 8; ++k) {
        y[k] = std::fabs(box.y[k]);
        z[k] = c.orthographic ? 0.0 : box.z[k];
    }
    const auto fits = [&](double d) {
        double from = -HUGE_VAL, to = HUGE_VAL;
        for (int k = 0; k < 8; ++k) {
            const double e = d + z[k];
            if (!(e > 0) || y[k] > roomUp * e)
                return false;
            from = std::max(from, x[k] - roomRight * e);
            to = std::min(to, x[k] - roomLeft * e);
        }
        return from <= to;
    };
    double high = 1e-6;
    for (int k = 0; k < 8; ++k) // beyond every corner's depth
        high = std::max(high, std::fabs(z[k]) + std::fabs(x[k]) + y[k]);
    for (int guard = 0; guard < 200 && !fits(high); ++guard)
        high *= 2;
    double low = 0;
    for (int k = 0; k < 60; ++k) {
        const double d = 0.5 * (low + high);
        (fits(d) ? high : low) = d;
    }
    c.distance = high;
    // Left gap minus right gap, (min + max) - (R - T) in tangents, falls as s grows.
    const auto lopsided = [&](double s) {
        double least = HUGE_VAL, most = -HUGE_VAL;
        for (int k = 0; k < 8; ++k) {
            const double t = (x[k] - s) / (high + z[k]);
            least = std::min(least, t), most = std::max(most, t);
        }
        return least + most - (R - T);
    };
    double span = 1e-6;
    for (int k = 0; k < 8; ++k)
        span = std::max(span, std::fabs(x[k]) + (T + R) * (high + std::fabs(z[k])));
    double sLow = -span, sHigh = span;
    for (int k = 0; k < 80; ++k) {
        const double s = 0.5 * (sLow + sHigh);
        (lopsided(s) > 0 ? sLow : sHigh) = s;
    }
    const double s = 0.5 * (sLow + sHigh);
    for (int k = 0; k < 3; ++k)
        c.target[k] += basis.right[k] * (std::isfinite(s) ? s : 0.0);
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
