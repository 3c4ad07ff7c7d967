#include "core/view/box_handles.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace faultline::core {

std::array<BoxHandle, 6> boxFaceHandles(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 mid = (lo + hi) * 0.5;
    std::array<BoxHandle, 6> handles{};
    for (int f = 0; f < 6; ++f) {
        const int axis = f / 2;
        const bool isMax = f % 2 == 1;
        glm::dvec3 c = mid;
        c[axis] = isMax ? hi[axis] : lo[axis];
        glm::dvec3 n(0.0);
        n[axis] = isMax ? 1.0 : -1.0;
        handles[f] = {static_cast<BoxFace>(f), c, n};
    }
    return handles;
}

double defaultHandleRadius(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 size = glm::abs(hi - lo);
    const double diag = glm::length(size);
    const double thinnest = std::min({size.x, size.y, size.z});
    double r = 0.04 * diag;
    if (thinnest > 0.0)
        r = std::min(r, thinnest / 3.0);
    return r > 0.0 ? r : 1e-3;
}

double screenHandleRadius(const glm::dvec3& lo, const glm::dvec3& hi, double cameraDistance,
                          double fovYDegrees) {
    const double halfFov = 0.5 * fovYDegrees * 3.14159265358979323846 / 180.0;
    const double viewHeight = 2.0 * cameraDistance * std::tan(halfFov);
    if (!(viewHeight > 0.0) || !std::isfinite(viewHeight))
        return defaultHandleRadius(lo, hi);
    double r = kHandleScreenShare * viewHeight;
    const glm::dvec3 size = glm::abs(hi - lo);
    const double thinnest = std::min({size.x, size.y, size.z});
    if (thinnest > 0.0)
        r = std::min(r, thinnest / 3.0);
    return r > 0.0 ? r : 1e-3;
}

std::optional<BoxFace> pickBoxFace(const glm::dvec3& lo, const glm::dvec3& hi, const Ray& ray,
                                   double handleRadius) {
    std::optional<BoxFace> best;
    double bestT = 0.0;
    for (const BoxHandle& h : boxFaceHandles(lo, hi)) {
        if (auto t = intersectSphere(ray, h.centre, handleRadius); t && (!best || *t < bestT)) {
            best = h.face;
            bestT = *t;
        }
    }
    if (best)
        return best;
    const auto hit = intersectBox(ray, lo, hi);
    if (!hit || hit->enterAxis < 0)
        return std::nullopt;
    const int axis = hit->enterAxis;
    // Entering through the min face means travelling towards +axis.
    const bool isMax = ray.direction[axis] < 0.0;
    return static_cast<BoxFace>(axis * 2 + (isMax ? 1 : 0));
}

std::optional<double> closestOnLine(const glm::dvec3& p, const glm::dvec3& axis, const Ray& ray) {
    // Minimise |p + s a - (o + t d)|: standard closest points of two lines.
    const glm::dvec3 w = p - ray.origin;
    const double a = glm::dot(axis, axis);
    const double b = glm::dot(axis, ray.direction);
    const double c = glm::dot(ray.direction, ray.direction);
    const double d = glm::dot(axis, w);
    const double e = glm::dot(ray.direction, w);
    const double denom = a * c - b * b;
    if (denom <= 1e-12 * a * c)
        return std::nullopt;
    return (b * e - c * d) / denom;
}

BoxBounds dragBoxFace(const glm::dvec3& lo, const glm::dvec3& hi, BoxFace face, const Ray& startRay,
                      const Ray& currentRay, double minSize) {
    BoxBounds out{lo, hi};
    const int axis = faceAxis(face);
    const BoxHandle handle = boxFaceHandles(lo, hi)[static_cast<int>(face)];
    glm::dvec3 dir(0.0);
    dir[axis] = 1.0;
    const auto s0 = closestOnLine(handle.centre, dir, startRay);
    const auto s1 = closestOnLine(handle.centre, dir, currentRay);
    if (!s0 || !s1)
        return out;
    const double delta = *s1 - *s0;
    minSize = std::max(minSize, 0.0);
    if (faceIsMax(face))
        out.hi[axis] = std::max(hi[axis] + delta, lo[axis] + minSize);
    else
        out.lo[axis] = std::min(lo[axis] + delta, hi[axis] - minSize);
    return out;
}

} // namespace faultline::core
