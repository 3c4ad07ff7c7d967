#include "core/view/screen_selection.hpp"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cassert>

namespace faultline::core {

bool projectToScreen(const ScreenMapping& mapping, double x, double y, double z, glm::dvec2& out) {
    const glm::dvec4 clip = mapping.viewProjection * glm::dvec4(x, y, z, 1.0);
    if (!(clip.w > 0.0) || clip.z < -clip.w || clip.z > clip.w)
        return false;
    const double nx = clip.x / clip.w, ny = clip.y / clip.w;
    out = glm::dvec2((nx * 0.5 + 0.5) * mapping.size.x, (0.5 - ny * 0.5) * mapping.size.y);
    return true;
}

bool insidePolygon(glm::dvec2 p, std::span<const glm::dvec2> polygon) {
    const std::size_t n = polygon.size();
    if (n < 3)
        return false;
    bool inside = false;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const glm::dvec2 a = polygon[i], b = polygon[j];
        // The edge straddles the horizontal line through p (half-open in y, so a vertex on the
        // line counts once) and crosses it to the right of p.
        if ((a.y > p.y) != (b.y > p.y)) {
            const double xCross = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < xCross)
                inside = !inside;
        }
    }
    return inside;
}

namespace {

template <class Inside>
std::vector<std::uint32_t> rowsWhere(const ScreenMapping& mapping, std::span<const float> x,
                                     std::span<const float> y, std::span<const float> z,
                                     std::span<const std::uint8_t> mask, Inside inside) {
    assert(x.size() == y.size() && x.size() == z.size());
    assert(mask.empty() || mask.size() == x.size());
    std::vector<std::uint32_t> rows;
    glm::dvec2 p;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        if (projectToScreen(mapping, x[i], y[i], z[i], p) && inside(p))
            rows.push_back(static_cast<std::uint32_t>(i));
    }
    return rows;
}

} // namespace

std::vector<std::uint32_t> rowsInRectangle(const ScreenMapping& mapping, std::span<const float> x,
                                           std::span<const float> y, std::span<const float> z,
                                           std::span<const std::uint8_t> mask, glm::dvec2 a,
                                           glm::dvec2 b) {
    const glm::dvec2 lo = glm::min(a, b), hi = glm::max(a, b);
    return rowsWhere(mapping, x, y, z, mask, [&](glm::dvec2 p) {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    });
}

std::vector<std::uint32_t> rowsInPolygon(const ScreenMapping& mapping, std::span<const float> x,
                                         std::span<const float> y, std::span<const float> z,
                                         std::span<const std::uint8_t> mask,
                                         std::span<const glm::dvec2> polygon) {
    if (polygon.size() < 3)
        return {};
    // The polygon's bounds first: most points of a small lasso fail there cheaply.
    glm::dvec2 lo = polygon[0], hi = polygon[0];
    for (const glm::dvec2& q : polygon)
        lo = glm::min(lo, q), hi = glm::max(hi, q);
    return rowsWhere(mapping, x, y, z, mask, [&](glm::dvec2 p) {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y &&
               insidePolygon(p, polygon);
    });
}

} // namespace faultline::core
