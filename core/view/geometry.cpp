#include "core/view/geometry.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace faultline::core {

std::optional<double> intersectSphere(const Ray& ray, const glm::dvec3& centre, double radius) {
    const glm::dvec3 oc = ray.origin - centre;
    const double b = glm::dot(oc, ray.direction);
    const double c = glm::dot(oc, oc) - radius * radius;
    if (c <= 0.0)
        return 0.0; // inside
    const double disc = b * b - c;
    if (disc < 0.0 || b > 0.0)
        return std::nullopt;
    return -b - std::sqrt(disc);
}

std::optional<SlabHit> intersectBox(const Ray& ray, const glm::dvec3& lo, const glm::dvec3& hi) {
    double tEnter = -std::numeric_limits<double>::infinity();
    double tExit = std::numeric_limits<double>::infinity();
    int axis = -1;
    for (int a = 0; a < 3; ++a) {
        const double d = ray.direction[a];
        const double o = ray.origin[a];
        if (std::abs(d) < 1e-300) {
            if (o < lo[a] || o > hi[a])
                return std::nullopt;
            continue;
        }
        double t0 = (lo[a] - o) / d;
        double t1 = (hi[a] - o) / d;
        if (t0 > t1)
            std::swap(t0, t1);
        if (t0 > tEnter) {
            tEnter = t0;
            axis = a;
        }
        tExit = std::min(tExit, t1);
    }
    if (tEnter > tExit || tExit < 0.0)
        return std::nullopt;
    return SlabHit{tEnter, tExit, tEnter >= 0.0 ? axis : -1};
}

BoundingSphere boundingSphereOf(std::span<const float> x, std::span<const float> y,
                                std::span<const float> z, std::span<const float> radius,
                                std::span<const std::uint8_t> mask) {
    assert(x.size() == y.size() && x.size() == z.size() && x.size() == radius.size());
    assert(mask.empty() || mask.size() == x.size());
    glm::dvec3 lo(std::numeric_limits<double>::infinity());
    glm::dvec3 hi(-std::numeric_limits<double>::infinity());
    bool any = false;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        const double r = radius[i];
        lo = glm::min(lo, glm::dvec3(x[i] - r, y[i] - r, z[i] - r));
        hi = glm::max(hi, glm::dvec3(x[i] + r, y[i] + r, z[i] + r));
        any = true;
    }
    if (!any)
        return {};
    const glm::dvec3 centre = (lo + hi) * 0.5;
    double r2 = 0.0;
    double maxR = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        const glm::dvec3 d = glm::dvec3(x[i], y[i], z[i]) - centre;
        r2 = std::max(r2, glm::dot(d, d));
        maxR = std::max(maxR, double(radius[i]));
    }
    // max distance + max radius: a slight over-estimate, never an under-estimate.
    return {centre, std::sqrt(r2) + maxR};
}

void Aabb::extend(const glm::dvec3& p) {
    lo = valid ? glm::min(lo, p) : p;
    hi = valid ? glm::max(hi, p) : p;
    valid = true;
}

void Aabb::extend(const Aabb& b) {
    if (b.valid) {
        extend(b.lo);
        extend(b.hi);
    }
}

Aabb boundsOf(std::span<const float> x, std::span<const float> y, std::span<const float> z,
              std::span<const float> radius, std::span<const std::uint8_t> mask) {
    assert(x.size() == y.size() && x.size() == z.size() && x.size() == radius.size());
    assert(mask.empty() || mask.size() == x.size());
    Aabb box;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        const double r = radius[i];
        box.extend(glm::dvec3(x[i] - r, y[i] - r, z[i] - r));
        box.extend(glm::dvec3(x[i] + r, y[i] + r, z[i] + r));
    }
    return box;
}

BoundingSphere enclose(const BoundingSphere& a, const BoundingSphere& b) {
    if (a.radius <= 0.0 && a.centre == glm::dvec3(0.0))
        return b;
    if (b.radius <= 0.0 && b.centre == glm::dvec3(0.0))
        return a;
    const glm::dvec3 d = b.centre - a.centre;
    const double dist = glm::length(d);
    if (dist + b.radius <= a.radius)
        return a;
    if (dist + a.radius <= b.radius)
        return b;
    const double r = 0.5 * (dist + a.radius + b.radius);
    const glm::dvec3 c = a.centre + d * ((r - a.radius) / dist);
    return {c, r};
}

} // namespace faultline::core
