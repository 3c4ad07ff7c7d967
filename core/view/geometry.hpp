// Small geometric primitives shared by the camera, picking and box handles: rays, bounding
// spheres, and the two intersection tests they need.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>

namespace faultline::core {

struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0}; // unit length
    glm::dvec3 at(double t) const { return origin + direction * t; }
};

struct BoundingSphere {
    glm::dvec3 centre{0.0};
    double radius = 0.0;
    bool operator==(const BoundingSphere&) const = default;
};

// Nearest t >= 0 where the ray enters the sphere (t = 0 when it starts inside); nullopt on a miss.
std::optional<double> intersectSphere(const Ray& ray, const glm::dvec3& centre, double radius);

// Entry and exit t of the ray through the box [lo, hi] (tEnter may be negative when the ray starts
// inside); nullopt on a miss or when the box lies behind the ray.
struct SlabHit {
    double tEnter;
    double tExit;
    int enterAxis; // 0, 1, 2: the axis of the face the ray enters through (-1 when inside)
};
std::optional<SlabHit> intersectBox(const Ray& ray, const glm::dvec3& lo, const glm::dvec3& hi);

// A sphere around every sphere whose mask byte is non-zero (all when mask is empty), radii
// included. Its centre is the centre of their bounding box. Radius 0 at the origin when none.
BoundingSphere boundingSphereOf(std::span<const float> x, std::span<const float> y,
                                std::span<const float> z, std::span<const float> radius,
                                std::span<const std::uint8_t> mask = {});

// Axis-aligned bounds of every sphere whose mask byte is non-zero (all when mask is empty), radii
// included; `valid` is false when there is none.
struct Aabb {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
    bool valid = false;
    void extend(const glm::dvec3& p);
    void extend(const Aabb& b);
};
Aabb boundsOf(std::span<const float> x, std::span<const float> y, std::span<const float> z,
              std::span<const float> radius, std::span<const std::uint8_t> mask = {});

// The smallest sphere of this construction around two spheres.
BoundingSphere enclose(const BoundingSphere& a, const BoundingSphere& b);

} // namespace faultline::core
