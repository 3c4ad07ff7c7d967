// Face handles of the selected cutting box: where they are, which one a mouse ray grabs, and how a
// drag moves that face. Pure geometry so the viewport, the renderer and tests share it.
#pragma once

#include "core/view/geometry.hpp"

#include <array>
#include <optional>

namespace faultline::core {

// 0: -x (west), 1: +x (east), 2: -y (south), 3: +y (north), 4: -z (bottom), 5: +z (top).
enum class BoxFace { MinX, MaxX, MinY, MaxY, MinZ, MaxZ };

inline int faceAxis(BoxFace f) { return static_cast<int>(f) / 2; }
inline bool faceIsMax(BoxFace f) { return static_cast<int>(f) % 2 == 1; }

struct BoxHandle {
    BoxFace face;
    glm::dvec3 centre; // the middle of the face
    glm::dvec3 normal; // outward unit normal
};

// One handle per face, in BoxFace order.
std::array<BoxHandle, 6> boxFaceHandles(const glm::dvec3& lo, const glm::dvec3& hi);

// A handle radius that reads well for this box: 4% of its diagonal, at most a third of its
// thinnest side so opposite handles do not merge.
double defaultHandleRadius(const glm::dvec3& lo, const glm::dvec3& hi);

// A handle radius of a constant size on screen: kHandleScreenShare of the view's height in world
// units at the camera's distance (2 distance tan(fovY / 2)), so handles neither swell when zoomed
// in nor vanish when zoomed out; at most a third of the box's thinnest side. The renderer and
// the viewport's picking use the same one.
inline constexpr double kHandleScreenShare = 0.012;
double screenHandleRadius(const glm::dvec3& lo, const glm::dvec3& hi, double cameraDistance,
                          double fovYDegrees);

// The face a ray grabs: the nearest handle sphere it hits, else the face through which it enters
// the box; nullopt when it misses both.
std::optional<BoxFace> pickBoxFace(const glm::dvec3& lo, const glm::dvec3& hi, const Ray& ray,
                                   double handleRadius);

// The box after dragging `face` from where `startRay` grabbed it to where `currentRay` points.
// The face moves along its axis by the change in the closest point of each ray to that axis, and
// stops `minSize` short of the opposite face. Rays parallel to the axis leave the box unchanged.
struct BoxBounds {
    glm::dvec3 lo;
    glm::dvec3 hi;
};
BoxBounds dragBoxFace(const glm::dvec3& lo, const glm::dvec3& hi, BoxFace face, const Ray& startRay,
                      const Ray& currentRay, double minSize = 0.0);

// Parameter s of the point on the line (p + s * axis) nearest to the ray; nullopt when parallel.
std::optional<double> closestOnLine(const glm::dvec3& p, const glm::dvec3& axis, const Ray& ray);

} // namespace faultline::core
