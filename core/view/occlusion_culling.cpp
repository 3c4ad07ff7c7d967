#include "core/view/occlusion_culling.hpp"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace faultline::core {

namespace {

// Window depth of a view-space z (negative in front of the eye).
double windowDepth(const SphereProjection& p, double zView) {
    const double clipZ = p.projection[2][2] * zView + p.projection[3][2];
    const double clipW = p.projection[2][3] * zView + p.projection[3][3];
    return 0.5 * (clipZ / clipW) + 0.5;
}

// Exact extent of a sphere's perspective projection along one screen axis: the planes through
// the eye that contain the other screen axis and touch the sphere (Mara & McGuire 2013).
// `a` is the view coordinate along the axis, `zc` the view depth (negative). Returns ndc bounds.
void perspectiveExtent(double a, double zc, double r, double scale, double& lo, double& hi) {
    const double l2 = a * a + zc * zc;
    const double t2 = l2 - r * r;
    if (t2 <= 0.0) {
        lo = -std::numeric_limits<double>::infinity();
        hi = std::numeric_limits<double>::infinity();
        return;
    }
    const double t = std::sqrt(t2);
    // Tangent directions: (a, zc) turned by +-asin(r / L), scaled by L.
    const double a0 = a * t - zc * r, z0 = zc * t + a * r;
    const double a1 = a * t + zc * r, z1 = zc * t - a * r;
    const double inf = std::numeric_limits<double>::infinity();
    const double p0 = z0 < 0.0 ? scale * a0 / -z0 : (a0 > 0 ? inf : -inf);
    const double p1 = z1 < 0.0 ? scale * a1 / -z1 : (a1 > 0 ? inf : -inf);
    lo = std::min(p0, p1);
    hi = std::max(p0, p1);
}

} // namespace

bool projectSphere(const SphereProjection& p, const glm::dvec3& centre, double radius,
                   SphereFootprint& out) {
    const glm::dmat4& v = p.view;
    const glm::dvec3 c(v[0][0] * centre.x + v[1][0] * centre.y + v[2][0] * centre.z + v[3][0],
                       v[0][1] * centre.x + v[1][1] * centre.y + v[2][1] * centre.z + v[3][1],
                       v[0][2] * centre.x + v[1][2] * centre.y + v[2][2] * centre.z + v[3][2]);
    const double r = std::max(radius, 0.0);
    // Near and far planes in view space (the projection maps -near to depth 0, -far to 1).
    const double p22 = p.projection[2][2], p32 = p.projection[3][2];
    double nearZ, farZ;
    if (p.perspective) {
        nearZ = -p32 / (p22 - 1.0); // -near
        farZ = -p32 / (p22 + 1.0);  // -far
    } else {
        nearZ = (-1.0 - p32) / p22;
        farZ = (1.0 - p32) / p22;
    }
    if (c.z - r > nearZ || c.z + r < farZ)
        return false; // wholly in front of the near plane's back side or beyond the far plane
    out.crossesNear = c.z + r > nearZ;

    double xlo, xhi, ylo, yhi;
    if (out.crossesNear) {
        xlo = ylo = -1.0;
        xhi = yhi = 1.0;
    } else if (p.perspective) {
        perspectiveExtent(c.x, c.z, r, p.projection[0][0], xlo, xhi);
        perspectiveExtent(c.y, c.z, r, p.projection[1][1], ylo, yhi);
    } else {
        const double cx = p.projection[0][0] * c.x + p.projection[3][0];
        const double cy = p.projection[1][1] * c.y + p.projection[3][1];
        xlo = cx - p.projection[0][0] * r, xhi = cx + p.projection[0][0] * r;
        ylo = cy - p.projection[1][1] * r, yhi = cy + p.projection[1][1] * r;
    }
    // Pixels whose centres may lie inside, widened by a pixel against rounding.
    const double w = p.width, h = p.height;
    const double px0 = std::floor((xlo * 0.5 + 0.5) * w - 0.5) - 1.0;
    const double px1 = std::ceil((xhi * 0.5 + 0.5) * w - 0.5) + 1.0;
    const double py0 = std::floor((ylo * 0.5 + 0.5) * h - 0.5) - 1.0;
    const double py1 = std::ceil((yhi * 0.5 + 0.5) * h - 0.5) + 1.0;
    if (px1 < 0.0 || py1 < 0.0 || px0 > w - 1 || py0 > h - 1)
        return false;
    out.x0 = static_cast<std::uint16_t>(std::clamp(px0, 0.0, w - 1));
    out.x1 = static_cast<std::uint16_t>(std::clamp(px1, 0.0, w - 1));
    out.y0 = static_cast<std::uint16_t>(std::clamp(py0, 0.0, h - 1));
    out.y1 = static_cast<std::uint16_t>(std::clamp(py1, 0.0, h - 1));
    out.nearDepth = out.crossesNear ? 0.0f : static_cast<float>(windowDepth(p, c.z + r) - 1e-6);
    return true;
}

void SphereOcclusionCuller::begin(std::span<const float> x, std::span<const float> y,
                                  std::span<const float> z, std::span<const float> radius,
                                  std::span<const std::uint32_t> rows,
                                  const SphereProjection& projection) {
    assert(projection.width > 0 && projection.height > 0);
    assert(projection.width <= 65535 && projection.height <= 65535);
    m_projection = projection;
    m_frustumCulled = 0;
    m_occlusionCulled = 0;
    // Project in parallel into place, marking the ones out of view, then compact.
    m_candidates.resize(rows.size());
    std::vector<std::uint8_t> inView(rows.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 8192),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i) {
                              const std::uint32_t row = rows[i];
                              SphereFootprint& f = m_candidates[i];
                              inView[i] = projectSphere(
                                  projection, glm::dvec3(x[row], y[row], z[row]), radius[row], f);
                              f.row = row;
                          }
                      });
    std::size_t out = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (inView[i])
            m_candidates[out++] = m_candidates[i];
    }
    m_frustumCulled = rows.size() - out;
    m_candidates.resize(out);
}

int SphereOcclusionCuller::autoTileSize() const {
    // About three quarters of the median footprint width (without its safety margin of about
    // three pixels): close to one front sphere per tile.
    std::vector<int> widths;
    const std::size_t step = std::max<std::size_t>(1, m_candidates.size() / 1024);
    for (std::size_t i = 0; i < m_candidates.size(); i += step)
        widths.push_back(int(m_candidates[i].x1) - int(m_candidates[i].x0) - 3);
    if (widths.empty())
        return 4;
    std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
    return std::clamp(widths[widths.size() / 2] * 3 / 4, 2, 64);
}

std::vector<std::uint32_t> SphereOcclusionCuller::takeOccluders(int tileSize) {
    if (tileSize <= 0)
        tileSize = autoTileSize();
    const int tw = (m_projection.width + tileSize - 1) / tileSize;
    const int th = (m_projection.height + tileSize - 1) / tileSize;
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> best(static_cast<std::size_t>(tw) * th, kNone);
    for (std::uint32_t i = 0; i < m_candidates.size(); ++i) {
        const SphereFootprint& f = m_candidates[i];
        if (f.crossesNear)
            continue;
        const int tx = ((f.x0 + f.x1) / 2) / tileSize;
        const int ty = ((f.y0 + f.y1) / 2) / tileSize;
        std::uint32_t& slot = best[static_cast<std::size_t>(ty) * tw + tx];
        if (slot == kNone || f.nearDepth < m_candidates[slot].nearDepth)
            slot = i;
    }
    std::vector<std::uint8_t> taken(m_candidates.size(), 0);
    std::vector<std::uint32_t> rows;
    for (std::uint32_t slot : best) {
        if (slot != kNone) {
            taken[slot] = 1;
            rows.push_back(m_candidates[slot].row);
        }
    }
    std::size_t out = 0;
    for (std::size_t i = 0; i < m_candidates.size(); ++i) {
        if (!taken[i])
            m_candidates[out++] = m_candidates[i];
    }
    m_candidates.resize(out);
    return rows;
}

void SphereOcclusionCuller::buildPyramid(std::span<const float> depth) {
    m_levels.resize(1);
    m_levelSize.assign(1, glm::ivec2(m_projection.width, m_projection.height));
    m_levels[0].clear(); // level 0 is read from `depth` directly
    glm::ivec2 size = m_levelSize[0];
    std::span<const float> prev = depth;
    while (size.x > 1 || size.y > 1) {
        const glm::ivec2 next((size.x + 1) / 2, (size.y + 1) / 2);
        std::vector<float> level(static_cast<std::size_t>(next.x) * next.y);
        for (int j = 0; j < next.y; ++j) {
            const int j0 = 2 * j, j1 = std::min(2 * j + 1, size.y - 1);
            for (int i = 0; i < next.x; ++i) {
                const int i0 = 2 * i, i1 = std::min(2 * i + 1, size.x - 1);
                level[static_cast<std::size_t>(j) * next.x + i] =
                    std::max(std::max(prev[std::size_t(j0) * size.x + i0],
                                      prev[std::size_t(j0) * size.x + i1]),
                             std::max(prev[std::size_t(j1) * size.x + i0],
                                      prev[std::size_t(j1) * size.x + i1]));
            }
        }
        m_levels.push_back(std::move(level));
        m_levelSize.push_back(next);
        prev = m_levels.back();
        size = next;
    }
}

float SphereOcclusionCuller::maxDepthOver(const SphereFootprint& f,
                                          std::span<const float> level0) const {
    // The finest level where the rectangle spans at most 4 x 4 texels.
    int x0 = f.x0, x1 = f.x1, y0 = f.y0, y1 = f.y1;
    std::size_t k = 0;
    while (k + 1 < m_levels.size() && (x1 - x0 > 3 || y1 - y0 > 3)) {
        x0 >>= 1, x1 >>= 1, y0 >>= 1, y1 >>= 1;
        ++k;
    }
    const std::span<const float> level = k == 0 ? level0 : std::span<const float>(m_levels[k]);
    const int w = m_levelSize[k].x;
    float m = 0.0f;
    for (int j = y0; j <= y1; ++j)
        for (int i = x0; i <= x1; ++i)
            m = std::max(m, level[static_cast<std::size_t>(j) * w + i]);
    return m;
}

void SphereOcclusionCuller::cullBehind(std::span<const float> depth) {
    assert(depth.size() == std::size_t(m_projection.width) * m_projection.height);
    buildPyramid(depth);
    std::vector<std::uint8_t> hidden(m_candidates.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_candidates.size(), 8192),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i) {
                              const SphereFootprint& f = m_candidates[i];
                              hidden[i] = !f.crossesNear && maxDepthOver(f, depth) < f.nearDepth;
                          }
                      });
    std::size_t out = 0;
    for (std::size_t i = 0; i < m_candidates.size(); ++i) {
        if (!hidden[i])
            m_candidates[out++] = m_candidates[i];
    }
    m_occlusionCulled += m_candidates.size() - out;
    m_candidates.resize(out);
}

std::vector<std::uint32_t> SphereOcclusionCuller::takeRemaining() {
    std::vector<std::uint32_t> rows;
    rows.reserve(m_candidates.size());
    for (const SphereFootprint& f : m_candidates)
        rows.push_back(f.row);
    m_candidates.clear();
    return rows;
}

} // namespace faultline::core
