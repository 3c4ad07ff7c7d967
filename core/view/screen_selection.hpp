// Selecting spheres by a shape drawn on a view: which sphere centres project inside a
// rectangle or a lasso (a closed polygon) in the view's pixels. Pure geometry, no GL.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace faultline::core {

// Where a view shows points: a world-to-clip matrix (projection x view, OpenGL conventions) and
// the viewport's size in pixels. Pixels have their origin at the top left, y down.
struct ScreenMapping {
    glm::dmat4 viewProjection{1.0};
    glm::dvec2 size{1.0, 1.0};
};

// The point in pixels, or false when it is not drawn: behind the eye (w <= 0) or outside the
// depth range between the near and far planes.
bool projectToScreen(const ScreenMapping& mapping, double x, double y, double z, glm::dvec2& out);

// Even-odd rule: inside when a ray from p crosses the polygon's edges an odd number of times
// (self-crossing lassos alternate in and out). The polygon closes itself (last point to first);
// fewer than 3 points enclose nothing. Points exactly on an edge may fall either way.
bool insidePolygon(glm::dvec2 p, std::span<const glm::dvec2> polygon);

// Rows whose mask byte is non-zero (every row when the mask is empty) whose centre projects
// inside the rectangle with corners a and b (any order, edges included), ascending.
std::vector<std::uint32_t> rowsInRectangle(const ScreenMapping& mapping, std::span<const float> x,
                                           std::span<const float> y, std::span<const float> z,
                                           std::span<const std::uint8_t> mask, glm::dvec2 a,
                                           glm::dvec2 b);

// Rows whose mask byte is non-zero (every row when the mask is empty) whose centre projects
// inside the polygon (insidePolygon), ascending.
std::vector<std::uint32_t> rowsInPolygon(const ScreenMapping& mapping, std::span<const float> x,
                                         std::span<const float> y, std::span<const float> z,
                                         std::span<const std::uint8_t> mask,
                                         std::span<const glm::dvec2> polygon);

// Of `candidates` (rows, e.g. those inside a rectangle), the ones the eye sees: front-most at a
// tenth or more of their disc's pixels (what peeks through the gap between touching spheres in
// front does not count), among every sphere whose mask byte is non-zero (every
// row when the mask is empty). A software depth buffer of the spheres' front caps at the view's
// pixels (at most 1024 on the long side), as OVITO's default selection takes what is visible.
// Ascending.
std::vector<std::uint32_t> frontmostRows(const ScreenMapping& mapping, std::span<const float> x,
                                         std::span<const float> y, std::span<const float> z,
                                         std::span<const float> radius,
                                         std::span<const std::uint8_t> mask,
                                         std::span<const std::uint32_t> candidates);

} // namespace faultline::core
