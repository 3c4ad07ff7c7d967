// FrameGrid (internal): every sphere of a frame binned in a dense grid, positions copied in
// cell order, to visit only the spheres near a plane patch (fault throw sampling) quickly.
#pragma once

#include "core/faults/plane_fit.hpp"
#include "core/model/frame.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace faultline::core::detail {

class FrameGrid {
  public:
    // About `spheresPerCell` finite spheres a cell on average; non-finite centres are left out.
    explicit FrameGrid(const Frame& frame, double spheresPerCell = 8.0);

    double cellSize() const { return m_cell; }
    std::size_t size() const { return m_rows.size(); }
    // Slot k (in cell order) holds frame row rows()[k] at (xs[k], ys[k], zs[k]).
    const std::vector<std::uint32_t>& rows() const { return m_rows; }
    const std::vector<float>& xs() const { return m_x; }
    const std::vector<float>& ys() const { return m_y; }
    const std::vector<float>& zs() const { return m_z; }

    // Calls visit(slot) for the spheres of every cell that meets the box [lo, hi], whose centre
    // lies within reach + half a cell diagonal of the plane through `point` with unit `normal`,
    // and for which acceptCell(cellCentre) is true. Cells are walked in columns along the
    // normal's dominant axis, so only the cells near the plane are ever looked at.
    template <typename AcceptCell, typename Visit>
    void forEachNearPlane(const Vec3d& lo, const Vec3d& hi, const Vec3d& point, const Vec3d& normal,
                          double reach, AcceptCell&& acceptCell, Visit&& visit) const;

  private:
    std::int64_t cellCoord(int axis, double v) const {
        const double c = std::floor((v - m_origin[axis]) / m_cell);
        if (!(c > 0))
            return 0;
        return std::min<std::int64_t>(m_dims[axis] - 1,
                                      static_cast<std::int64_t>(std::min(c, 1e9)));
    }

    Vec3d m_origin{0, 0, 0};
    double m_cell = 1;
    std::int64_t m_dims[3] = {1, 1, 1};
    std::vector<std::uint32_t> m_start; // per cell, + 1
    std::vector<std::uint32_t> m_rows;
    std::vector<float> m_x, m_y, m_z;
};

template <typename AcceptCell, typename Visit>
void FrameGrid::forEachNearPlane(const Vec3d& lo, const Vec3d& hi, const Vec3d& point,
                                 const Vec3d& normal, double reach, AcceptCell&& acceptCell,
                                 Visit&& visit) const {
    if (m_rows.empty())
        return;
    // a: the axis the normal is most along; b, c: the other two (the column grid).
    int a = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(normal[k]) > std::fabs(normal[a]))
            a = k;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    std::int64_t first[3], last[3];
    for (int k = 0; k < 3; ++k) {
        first[k] = cellCoord(k, lo[k]);
        last[k] = cellCoord(k, hi[k]);
    }
    const double slack = reach + m_cell * std::sqrt(3.0) / 2;
    std::int64_t index[3];
    Vec3d centre;
    for (index[b] = first[b]; index[b] <= last[b]; ++index[b])
        for (index[c] = first[c]; index[c] <= last[c]; ++index[c]) {
            centre[b] = m_origin[b] + (double(index[b]) + 0.5) * m_cell;
            centre[c] = m_origin[c] + (double(index[c]) + 0.5) * m_cell;
            // Along a, the plane distance of a cell centre runs linearly; keep |s| <= slack.
            const double s0 =
                normal[b] * (centre[b] - point[b]) + normal[c] * (centre[c] - point[c]);
            double t0 = point[a] + (-slack - s0) / normal[a];
            double t1 = point[a] + (slack - s0) / normal[a];
            if (t0 > t1)
                std::swap(t0, t1);
            const double i0 = std::ceil((t0 - m_origin[a]) / m_cell - 0.5);
            const double i1 = std::floor((t1 - m_origin[a]) / m_cell - 0.5);
            const std::int64_t from =
                std::max<std::int64_t>(first[a], std::int64_t(std::max(i0, -1.0)));
            const std::int64_t to =
                std::min<std::int64_t>(last[a], std::int64_t(std::min(i1, 1e9)));
            for (index[a] = from; index[a] <= to; ++index[a]) {
                centre[a] = m_origin[a] + (double(index[a]) + 0.5) * m_cell;
                if (!acceptCell(centre))
                    continue;
                const std::size_t cell =
                    std::size_t(index[0] + m_dims[0] * (index[1] + m_dims[1] * index[2]));
                for (std::uint32_t k = m_start[cell]; k < m_start[cell + 1]; ++k)
                    visit(k);
            }
        }
}

} // namespace faultline::core::detail
