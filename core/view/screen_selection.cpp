#include "core/view/screen_selection.hpp"

#include <glm/glm.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

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

std::vector<std::uint32_t> frontmostRows(const ScreenMapping& mapping, std::span<const float> x,
                                         std::span<const float> y, std::span<const float> z,
                                         std::span<const float> radius,
                                         std::span<const std::uint8_t> mask,
                                         std::span<const std::uint32_t> candidates) {
    if (candidates.empty())
        return {};
    // The depth buffer at most 1024 pixels on its long side.
    const double scale = std::min(1.0, 1024.0 / std::max({mapping.size.x, mapping.size.y, 1.0}));
    const int w = std::max(1, static_cast<int>(std::ceil(mapping.size.x * scale)));
    const int h = std::max(1, static_cast<int>(std::ceil(mapping.size.y * scale)));
    std::vector<float> depth(std::size_t(w) * h, std::numeric_limits<float>::infinity());
    std::vector<std::uint32_t> owner(std::size_t(w) * h, ~std::uint32_t(0));
    std::vector<std::uint32_t> discPixels(x.size(), 0); // each sphere's disc, on screen
    const glm::dmat4& m = mapping.viewProjection;
    const glm::dmat4 inverse = glm::inverse(m);
    auto ndcOf = [&](const glm::dvec3& p, glm::dvec3& out) {
        const glm::dvec4 c = m * glm::dvec4(p, 1.0);
        if (c.w <= 0)
            return false;
        out = glm::dvec3(c) / c.w;
        return true;
    };
    auto pixelOf = [&](const glm::dvec3& ndc) {
        return glm::dvec2((ndc.x + 1) * 0.5 * w, (1 - ndc.y) * 0.5 * h);
    };
    for (std::size_t row = 0; row < x.size(); ++row) {
        if (!mask.empty() && !mask[row])
            continue;
        const glm::dvec3 c(x[row], y[row], z[row]);
        glm::dvec3 ndc;
        if (!ndcOf(c, ndc) || ndc.z < -1 || ndc.z > 1)
            continue;
        // The ray through the centre, then the sphere's nearest point and its edge on screen.
        const glm::dvec4 a = inverse * glm::dvec4(ndc.x, ndc.y, -1, 1),
                         b = inverse * glm::dvec4(ndc.x, ndc.y, 1, 1);
        const glm::dvec3 d = glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
        const glm::dvec3 side = glm::normalize(
            glm::cross(d, std::fabs(d.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
        const double r = radius.empty() ? 0.5 : radius[row];
        glm::dvec3 front, edge;
        if (!ndcOf(c - r * d, front) || !ndcOf(c + r * side, edge))
            front = ndc, edge = ndc;
        const glm::dvec2 centre = pixelOf(ndc);
        const double pr = std::max(0.5, glm::length(pixelOf(edge) - centre));
        const double cap = ndc.z - front.z; // how much nearer the front is than the centre
        const int x0 = std::max(0, static_cast<int>(std::floor(centre.x - pr)));
        const int x1 = std::min(w - 1, static_cast<int>(std::ceil(centre.x + pr)));
        const int y0 = std::max(0, static_cast<int>(std::floor(centre.y - pr)));
        const int y1 = std::min(h - 1, static_cast<int>(std::ceil(centre.y + pr)));
        for (int py = y0; py <= y1; ++py)
            for (int px = x0; px <= x1; ++px) {
                const double dx = px + 0.5 - centre.x, dy = py + 0.5 - centre.y;
                const double rho2 = (dx * dx + dy * dy) / (pr * pr);
                if (rho2 > 1 && !(px == int(centre.x) && py == int(centre.y)))
                    continue; // outside the disc (a sub-pixel sphere keeps its centre pixel)
                ++discPixels[row];
                const float at =
                    static_cast<float>(ndc.z - cap * std::sqrt(std::max(0.0, 1 - rho2)));
                const std::size_t k = std::size_t(py) * w + px;
                if (at < depth[k])
                    depth[k] = at, owner[k] = static_cast<std::uint32_t>(row);
            }
    }
    // Seen: owning a tenth of its disc's pixels or more (one pixel for a sphere under four),
    // so spheres that only peek through the gaps between touching ones in front stay out.
    std::vector<std::uint32_t> pixels(x.size(), 0);
    for (std::uint32_t o : owner)
        if (o < pixels.size())
            ++pixels[o];
    std::vector<std::uint32_t> out;
    for (std::uint32_t row : candidates)
        if (row < pixels.size() && pixels[row] > 0 && pixels[row] >= discPixels[row] / 10)
            out.push_back(row);
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace faultline::core
