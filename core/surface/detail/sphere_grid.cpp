#include "core/surface/detail/sphere_grid.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::core::detail {

SphereGrid::SphereGrid(const PackedSpheres& s, const Box& centres, float cell) {
    const std::size_t n = s.size();
    double extent[3];
    for (int k = 0; k < 3; ++k)
        extent[k] = std::max(0.0, double(centres.hi[k]) - double(centres.lo[k]));
    double size = std::max(double(cell), 1e-6);
    auto cells = [&](double c) {
        double total = 1.0;
        for (int k = 0; k < 3; ++k)
            total *= std::floor(extent[k] / c) + 1.0;
        return total;
    };
    while (cells(size) > double(kMaxCells))
        size *= 1.25;
    m_cell = static_cast<float>(size);
    m_inverse = 1.0f / m_cell;
    for (int k = 0; k < 3; ++k) {
        m_lo[k] = centres.lo[k];
        m_dims[k] = static_cast<int>(std::floor(extent[k] / size)) + 1;
    }
    const std::size_t total = std::size_t(m_dims[0]) * m_dims[1] * m_dims[2];
    auto cellOf = [&](std::size_t i) {
        const float c[3] = {s.x[i], s.y[i], s.z[i]};
        int idx[3];
        for (int k = 0; k < 3; ++k)
            idx[k] = std::clamp(static_cast<int>(std::floor((c[k] - m_lo[k]) * m_inverse)), 0,
                                m_dims[k] - 1);
        return (std::size_t(idx[0]) * m_dims[1] + idx[1]) * m_dims[2] + idx[2];
    };
    // Counting sort by cell.
    m_start.assign(total + 1, 0);
    std::vector<std::uint32_t> cellIndex(n);
    for (std::size_t i = 0; i < n; ++i) {
        cellIndex[i] = static_cast<std::uint32_t>(cellOf(i));
        ++m_start[cellIndex[i] + 1];
    }
    for (std::size_t c = 0; c < total; ++c)
        m_start[c + 1] += m_start[c];
    std::vector<std::uint32_t> next(m_start.begin(), m_start.end() - 1);
    auto& p = m_spheres;
    for (auto* v : {&p.x, &p.y, &p.z, &p.r, &p.red, &p.green, &p.blue})
        v->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t to = next[cellIndex[i]]++;
        p.x[to] = s.x[i], p.y[to] = s.y[i], p.z[to] = s.z[i], p.r[to] = s.r[i];
        p.red[to] = s.red[i], p.green[to] = s.green[i], p.blue[to] = s.blue[i];
    }
}

void SphereGrid::gather(const Box& box, float reach, NearList& out, bool withColor) const {
    if (m_start.empty())
        return;
    // The cells under the reach box, a little wider than the reach so that rounding in the
    // cell index never drops a sphere the test below keeps.
    const float wide = reach * 1.0001f + 1e-6f * m_cell;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        const float a = (box.lo[k] - wide - m_lo[k]) * m_inverse;
        const float b = (box.hi[k] + wide - m_lo[k]) * m_inverse;
        if (!(b >= 0.0f) || !(a < float(m_dims[k])))
            return; // all of the grid lies on one side (or the box is not finite)
        lo[k] = std::max(0, static_cast<int>(std::floor(a)));
        hi[k] = std::min(m_dims[k] - 1, static_cast<int>(std::floor(b)));
    }
    const float reach2 = reach * reach;
    const auto& p = m_spheres;
    for (int ix = lo[0]; ix <= hi[0]; ++ix)
        for (int iy = lo[1]; iy <= hi[1]; ++iy) {
            const std::size_t column = (std::size_t(ix) * m_dims[1] + iy) * m_dims[2];
            const std::uint32_t first = m_start[column + lo[2]], last = m_start[column + hi[2] + 1];
            for (std::uint32_t i = first; i < last; ++i)
                appendIfWithin(p, i, box, reach2, out, withColor); // as the tree's gather
        }
}

} // namespace faultline::core::detail
