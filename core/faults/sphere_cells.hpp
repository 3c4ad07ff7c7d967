// SphereCells (internal): chosen spheres of a frame binned in a sparse uniform grid, positions
// copied in cell order, so neighbour searches within one cell size visit 27 cells.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace faultline::core::detail {

class SphereCells {
  public:
    // `rows`: frame rows with finite centres and radii (the caller's filter). Cells are at
    // least `cell` wide (grown so no axis has more than 2^20). Slots are sorted by cell, then by
    // particle id, so nothing downstream depends on the frame's row order.
    SphereCells(const Frame& frame, std::span<const std::uint32_t> rows, double cell);

    std::size_t size() const { return row.size(); }
    double cellSize() const { return m_cell; }
    std::size_t cellCount() const { return m_cellKey.size(); }
    std::uint32_t cellBegin(std::size_t c) const { return m_cellBegin[c]; }
    std::uint32_t cellEnd(std::size_t c) const { return m_cellBegin[c + 1]; }
    std::uint32_t cellOf(std::uint32_t slot) const { return m_cellOfSlot[slot]; }

    // Slot k holds frame row row[k], centre (x, y, z)[k] and radius r[k].
    std::vector<std::uint32_t> row;
    std::vector<float> x, y, z, r;

    // Calls f(otherCell) for every occupied cell among the 27 around cell c, c included (with
    // reach 2, the 125 within two cells).
    template <typename F> void forEachNeighbourCell(std::size_t c, F&& f, int reach = 1) const {
        const std::uint64_t key = m_cellKey[c];
        const std::int64_t cx = static_cast<std::int64_t>(key % m_dims[0]);
        const std::int64_t cy = static_cast<std::int64_t>((key / m_dims[0]) % m_dims[1]);
        const std::int64_t cz = static_cast<std::int64_t>(key / m_dims[0] / m_dims[1]);
        for (std::int64_t nz = cz - reach; nz <= cz + reach; ++nz)
            for (std::int64_t ny = cy - reach; ny <= cy + reach; ++ny)
                for (std::int64_t nx = cx - reach; nx <= cx + reach; ++nx) {
                    if (nx < 0 || ny < 0 || nz < 0 || nx >= std::int64_t(m_dims[0]) ||
                        ny >= std::int64_t(m_dims[1]) || nz >= std::int64_t(m_dims[2]))
                        continue;
                    const std::int64_t other =
                        find(std::uint64_t(nx) +
                             m_dims[0] * (std::uint64_t(ny) + m_dims[1] * std::uint64_t(nz)));
                    if (other >= 0)
                        f(static_cast<std::size_t>(other));
                }
    }

  private:
    std::int64_t find(std::uint64_t key) const;

    double m_cell = 1;
    std::uint64_t m_dims[3] = {1, 1, 1};
    std::vector<std::uint64_t> m_cellKey;    // per cell, ascending
    std::vector<std::uint32_t> m_cellBegin;  // per cell, + 1
    std::vector<std::uint32_t> m_cellOfSlot; // per slot
    // Cell key -> cell index: a dense table when the grid is small enough, else open addressing.
    std::vector<std::int32_t> m_dense;
    std::size_t m_mask = 0;
    std::vector<std::uint64_t> m_slotKey;
    std::vector<std::uint32_t> m_slotCell;
};

// Rows with visible[row] != 0 whose centre and radius are finite (radius >= 0).
std::vector<std::uint32_t> linkableRows(const Frame& frame, std::span<const std::uint8_t> visible);

} // namespace faultline::core::detail
