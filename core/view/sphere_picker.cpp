#include "core/view/sphere_picker.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace faultline::core {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

void SpherePicker::build(std::span<const float> x, std::span<const float> y,
                         std::span<const float> z, std::span<const float> radius,
                         std::span<const std::uint8_t> mask) {
    assert(x.size() == y.size() && x.size() == z.size() && x.size() == radius.size());
    assert(mask.empty() || mask.size() == x.size());
    m_x = x, m_y = y, m_z = z, m_r = radius;
    m_count = 0;
    m_rows.clear();
    m_cellStart.clear();
    m_dims = {0, 0, 0};

    glm::dvec3 lo(kInf), hi(-kInf);
    double maxR = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        const double r = std::max(0.0f, radius[i]);
        lo = glm::min(lo, glm::dvec3(x[i] - r, y[i] - r, z[i] - r));
        hi = glm::max(hi, glm::dvec3(x[i] + r, y[i] + r, z[i] + r));
        maxR = std::max(maxR, r);
        ++m_count;
    }
    if (m_count == 0)
        return;
    const glm::dvec3 size = glm::max(hi - lo, glm::dvec3(1e-9));
    // About two spheres per cell, but never cells smaller than a sphere (each sphere then sits in
    // at most 8 cells) and never more than 2^24 cells.
    const double volume = size.x * size.y * size.z;
    double cell = std::cbrt(volume / std::max<double>(1.0, m_count / 2.0));
    cell = std::max(cell, 2.0 * maxR);
    for (;;) {
        const glm::dvec3 d = glm::ceil(size / cell);
        if (d.x * d.y * d.z <= double(1 << 24))
            break;
        cell *= 1.26;
    }
    m_lo = lo;
    m_hi = hi;
    m_cell = glm::dvec3(cell);
    m_dims = glm::max(glm::ivec3(glm::ceil(size / cell)), glm::ivec3(1));

    const std::size_t cells = std::size_t(m_dims.x) * m_dims.y * m_dims.z;
    std::vector<std::uint32_t> counts(cells + 1, 0);
    auto forEachCell = [&](std::size_t i, auto&& fn) {
        const double r = std::max(0.0f, radius[i]);
        const glm::dvec3 c(x[i], y[i], z[i]);
        const glm::ivec3 a =
            glm::clamp(glm::ivec3(glm::floor((c - r - m_lo) / m_cell)), glm::ivec3(0), m_dims - 1);
        const glm::ivec3 b =
            glm::clamp(glm::ivec3(glm::floor((c + r - m_lo) / m_cell)), glm::ivec3(0), m_dims - 1);
        for (int k = a.z; k <= b.z; ++k)
            for (int j = a.y; j <= b.y; ++j)
                for (int ii = a.x; ii <= b.x; ++ii)
                    fn(cellIndex(ii, j, k));
    };
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        forEachCell(i, [&](std::size_t c) { ++counts[c + 1]; });
    }
    for (std::size_t c = 0; c < cells; ++c)
        counts[c + 1] += counts[c];
    m_cellStart = counts;
    m_rows.resize(counts[cells]);
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.empty() && !mask[i])
            continue;
        forEachCell(i, [&](std::size_t c) { m_rows[counts[c]++] = static_cast<std::uint32_t>(i); });
    }
}

std::optional<SphereHit> SpherePicker::pick(const Ray& ray) const {
    if (m_count == 0)
        return std::nullopt;
    const auto box = intersectBox(ray, m_lo, m_hi);
    if (!box)
        return std::nullopt;
    const double tStart = std::max(0.0, box->tEnter);
    const glm::dvec3 p = ray.at(tStart);
    glm::ivec3 cell =
        glm::clamp(glm::ivec3(glm::floor((p - m_lo) / m_cell)), glm::ivec3(0), m_dims - 1);
    // 3-D DDA (Amanatides & Woo): t at which the ray crosses the next cell wall on each axis.
    glm::ivec3 step;
    glm::dvec3 tNext, tDelta;
    for (int a = 0; a < 3; ++a) {
        const double d = ray.direction[a];
        if (d > 0) {
            step[a] = 1;
            tNext[a] = (m_lo[a] + (cell[a] + 1) * m_cell[a] - ray.origin[a]) / d;
            tDelta[a] = m_cell[a] / d;
        } else if (d < 0) {
            step[a] = -1;
            tNext[a] = (m_lo[a] + cell[a] * m_cell[a] - ray.origin[a]) / d;
            tDelta[a] = -m_cell[a] / d;
        } else {
            step[a] = 0;
            tNext[a] = kInf;
            tDelta[a] = kInf;
        }
    }
    std::optional<SphereHit> best;
    for (;;) {
        const std::size_t c = cellIndex(cell.x, cell.y, cell.z);
        for (std::uint32_t k = m_cellStart[c]; k < m_cellStart[c + 1]; ++k) {
            const std::uint32_t row = m_rows[k];
            const glm::dvec3 centre(m_x[row], m_y[row], m_z[row]);
            const auto t = intersectSphere(ray, centre, std::max(0.0f, m_r[row]));
            if (t && (!best || *t < best->t))
                best = SphereHit{row, *t, ray.at(*t)};
        }
        const double tCellExit = std::min({tNext.x, tNext.y, tNext.z});
        // A hit inside this cell cannot be beaten by a sphere met only in later cells.
        if (best && best->t <= tCellExit)
            return best;
        const int axis =
            tNext.x <= tNext.y ? (tNext.x <= tNext.z ? 0 : 2) : (tNext.y <= tNext.z ? 1 : 2);
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= m_dims[axis] || tNext[axis] > box->tExit)
            return best;
        tNext[axis] += tDelta[axis];
    }
}

} // namespace faultline::core
