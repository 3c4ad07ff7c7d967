#include "core/view/camera.hpp"
#include "core/util/enum_names.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

namespace faultline::core {

namespace {

constexpr double kPi = 3.14159265358979323846;

double tanHalfFov(const Camera& c) {
    return std::tan(std::clamp(c.fovYDegrees, 1.0, 170.0) * kPi / 360.0);
}

// Point on the unit trackball (Bell's: a sphere in the middle, a hyperbolic sheet outside).
glm::dvec3 trackballPoint(glm::dvec2 p) {
    const double r2 = glm::dot(p, p);
    const double z = r2 <= 0.5 ? std::sqrt(1.0 - r2) : 0.5 / std::sqrt(r2);
    return glm::normalize(glm::dvec3(p, z));
}

} // namespace

namespace {
constexpr EnumName<Projection> kProjections[] = {{Projection::Perspective, "perspective"},
                                                 {Projection::Orthographic, "orthographic"},
                                                 {Projection::Orthographic, "ortho"}};
constexpr EnumName<ViewPreset> kViewPresets[] = {
    {ViewPreset::Front, "front"}, {ViewPreset::Back, "back"}, {ViewPreset::Left, "left"},
    {ViewPreset::Side, "side"},   {ViewPreset::Top, "top"},   {ViewPreset::Bottom, "bottom"},
    {ViewPreset::Iso, "iso"},     {ViewPreset::Side, "right"}};
} // namespace

std::string_view projectionName(Projection p) { return nameIn(kProjections, p, "perspective"); }

std::optional<Projection> parseProjection(std::string_view name) {
    return valueIn(kProjections, name, NameCase::Ignore);
}

std::string_view viewPresetName(ViewPreset p) { return nameIn(kViewPresets, p, "front"); }

std::optional<ViewPreset> parseViewPreset(std::string_view name) {
    return valueIn(kViewPresets, name, NameCase::Ignore);
}

glm::dvec3 Camera::forward() const { return orientation * glm::dvec3(0.0, 0.0, -1.0); }
glm::dvec3 Camera::up() const { return orientation * glm::dvec3(0.0, 1.0, 0.0); }
glm::dvec3 Camera::right() const { return orientation * glm::dvec3(1.0, 0.0, 0.0); }
glm::dvec3 Camera::eye() const { return target - forward() * distance; }
double Camera::viewHeightAtTarget() const { return 2.0 * distance * tanHalfFov(*this); }

glm::dquat lookRotation(const glm::dvec3& forward, const glm::dvec3& up) {
    const glm::dvec3 back = -glm::normalize(forward);
    glm::dvec3 right = glm::cross(up, back);
    if (glm::dot(right, right) < 1e-24) // up parallel to forward: any perpendicular will do
        right =
            glm::cross(std::abs(back.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0), back);
    right = glm::normalize(right);
    const glm::dvec3 trueUp = glm::cross(back, right);
    return glm::normalize(glm::quat_cast(glm::dmat3(right, trueUp, back)));
}

glm::dmat4 viewMatrix(const Camera& c) {
    const glm::dmat3 rot = glm::mat3_cast(glm::normalize(c.orientation));
    const glm::dmat3 inv = glm::transpose(rot);
    glm::dmat4 m(inv);
    m[3] = glm::dvec4(-(inv * c.eye()), 1.0);
    return m;
}

glm::dmat4 projectionMatrix(const Camera& c, double aspect, ClipRange clip) {
    if (c.projection == Projection::Orthographic) {
        const double h = 0.5 * c.viewHeightAtTarget();
        return glm::ortho(-h * aspect, h * aspect, -h, h, clip.nearClip, clip.farClip);
    }
    return glm::perspective(2.0 * std::atan(tanHalfFov(c)), aspect, clip.nearClip, clip.farClip);
}

ClipRange clipRangeFor(const Camera& c, const BoundingSphere& scene) {
    const double r = std::max(scene.radius, 1e-9) * 1.02;
    const double depth = glm::dot(scene.centre - c.eye(), c.forward());
    double farClip = depth + r;
    double nearClip = depth - r;
    if (c.projection == Projection::Perspective) {
        // Depth precision: keep near at least far / 10^4 away, and in front of the eye.
        farClip = std::max(farClip, 1e-6);
        nearClip = std::max(nearClip, farClip * 1e-4);
    } else if (farClip - nearClip < 1e-9) {
        farClip = nearClip + 1e-9;
    }
    return {nearClip, farClip};
}

Ray cameraRay(const Camera& c, glm::dvec2 ndc, double aspect) {
    const double h = tanHalfFov(c);
    const glm::dvec3 f = c.forward(), u = c.up(), r = c.right();
    if (c.projection == Projection::Orthographic) {
        const double halfH = c.distance * h;
        const glm::dvec3 onTarget = c.target + r * (ndc.x * halfH * aspect) + u * (ndc.y * halfH);
        // Start well behind the eye so geometry between eye and target is in front of the ray.
        return {onTarget - f * (c.distance * 1e3 + 1e3), f};
    }
    const glm::dvec3 dir = glm::normalize(f + r * (ndc.x * h * aspect) + u * (ndc.y * h));
    return {c.eye(), dir};
}

void orbitTrackball(Camera& c, glm::dvec2 fromNdc, glm::dvec2 toNdc, double aspect) {
    // Round ball: scale x by the aspect so a drag of equal pixels turns equally in x and y.
    const glm::dvec2 scale(std::max(aspect, 1.0), std::max(1.0 / aspect, 1.0));
    const glm::dvec3 p0 = trackballPoint(fromNdc * scale);
    const glm::dvec3 p1 = trackballPoint(toNdc * scale);
    const glm::dvec3 axis = glm::cross(p0, p1);
    const double s = glm::length(axis);
    if (s < 1e-12)
        return;
    const double angle = std::atan2(s, glm::dot(p0, p1));
    // The scene turns by R in camera space, so the camera turns by R^-1 around the target.
    const glm::dquat sceneTurn = glm::angleAxis(angle, axis / s);
    c.orientation = glm::normalize(c.orientation * glm::inverse(sceneTurn));
}

void orbitTurntable(Camera& c, double yaw, double pitch) {
    const glm::dvec3 zUp(0.0, 0.0, 1.0);
    glm::dvec3 f = c.forward();
    // Pitch, clamped 1 degree short of the poles.
    const double elevation = std::asin(std::clamp(-f.z, -1.0, 1.0)); // > 0 when looking down
    const double limit = kPi / 2 - kPi / 180;
    const double target = std::clamp(elevation + pitch, -limit, limit);
    glm::dvec3 horiz(f.x, f.y, 0.0);
    if (glm::dot(horiz, horiz) < 1e-18)
        horiz = c.up(); // looking straight down or up: the screen's up gives the heading
    horiz.z = 0.0;
    horiz = glm::normalize(horiz);
    const glm::dquat yawTurn = glm::angleAxis(-yaw, zUp);
    horiz = yawTurn * horiz;
    f = horiz * std::cos(target) - zUp * std::sin(target);
    c.orientation = lookRotation(f, zUp);
}

void pan(Camera& c, glm::dvec2 deltaNdc, double aspect) {
    const double halfH = 0.5 * c.viewHeightAtTarget();
    c.target -= c.right() * (deltaNdc.x * halfH * aspect) + c.up() * (deltaNdc.y * halfH);
}

void zoomToCursor(Camera& c, double factor, glm::dvec2 cursorNdc, double aspect) {
    if (!(factor > 0.0))
        return;
    const double halfH = 0.5 * c.viewHeightAtTarget();
    const glm::dvec3 underCursor =
        c.target + c.right() * (cursorNdc.x * halfH * aspect) + c.up() * (cursorNdc.y * halfH);
    c.target = underCursor + (c.target - underCursor) / factor;
    c.distance /= factor;
}

void fitSphere(Camera& c, const BoundingSphere& s, double aspect, double margin) {
    c.target = s.centre;
    const double r = std::max(s.radius, 1e-9) * margin;
    const double tanY = tanHalfFov(c);
    const double tanX = tanY * std::max(aspect, 1e-6);
    const double tanMin = std::min(tanX, tanY);
    if (c.projection == Projection::Orthographic) {
        c.distance = r / tanMin;
    } else {
        // The sphere touches the narrower side of the view cone.
        c.distance = r / std::sin(std::atan(tanMin));
    }
}

void fitBox(Camera& c, const Aabb& box, double aspect, double margin) {
    if (!box.valid)
        return;
    c.target = (box.lo + box.hi) * 0.5;
    const double tanY = tanHalfFov(c) / margin;
    const double tanX = tanY * std::max(aspect, 1e-6);
    const glm::dvec3 r = c.right(), u = c.up(), f = c.forward();
    double d = 1e-9;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                                i & 4 ? box.hi.z : box.lo.z);
        const glm::dvec3 o = corner - c.target;
        const double x = std::abs(glm::dot(o, r)), y = std::abs(glm::dot(o, u));
        if (c.projection == Projection::Orthographic) {
            d = std::max({d, x / tanX, y / tanY});
        } else {
            // The corner at depth d + dot(o, f) must satisfy |x| <= tanX * depth (and y).
            const double depth = glm::dot(o, f);
            d = std::max({d, x / tanX - depth, y / tanY - depth});
        }
    }
    if (c.projection == Projection::Perspective) {
        // Keep the eye outside the box.
        const double reach = 0.5 * glm::length(box.hi - box.lo);
        d = std::max(d, reach * 1.05);
    }
    c.distance = d;
}

void applyPreset(Camera& c, ViewPreset preset) {
    const glm::dvec3 zUp(0, 0, 1), north(0, 1, 0);
    switch (preset) {
    case ViewPreset::Front:
        c.orientation = lookRotation({0, 1, 0}, zUp);
        break;
    case ViewPreset::Back:
        c.orientation = lookRotation({0, -1, 0}, zUp);
        break;
    case ViewPreset::Left:
        c.orientation = lookRotation({1, 0, 0}, zUp);
        break;
    case ViewPreset::Side:
        c.orientation = lookRotation({-1, 0, 0}, zUp);
        break;
    case ViewPreset::Top:
        c.orientation = lookRotation({0, 0, -1}, north);
        break;
    case ViewPreset::Bottom:
        c.orientation = lookRotation({0, 0, 1}, north);
        break;
    case ViewPreset::Iso: {
        const double az = 200.0 * kPi / 180.0; // eye bearing from the target, clockwise from north
        const double el = 30.0 * kPi / 180.0;
        const glm::dvec3 toEye(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el),
                               std::sin(el));
        c.orientation = lookRotation(-toEye, zUp);
        break;
    }
    }
}

} // namespace faultline::core
