// SphereGrid: the spheres bucketed in a uniform grid of cubic cells, z fastest, so the spheres of
// a run of cells along z lie next to each other. Gathering the spheres within reach of a block
// visits the columns of cells under the reach box, one contiguous range each, where the kd-tree
// (SphereTree) opened dozens of nodes to find a few dozen spheres of a sparse selection.
#pragma once

#include "core/surface/detail/sphere_tree.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace faultline::core::detail {

class SphereGrid {
  public:
    SphereGrid() = default;
    // Cells of about `cell` world units over `centres` (the spheres' centre box); larger when
    // that would make more than kMaxCells cells.
    SphereGrid(const PackedSpheres& spheres, const Box& centres, float cell);

    // Appends every sphere whose centre lies within `reach` of `box`: the same spheres as
    // SphereTree::gather, in cell order.
    void gather(const Box& box, float reach, NearList& out, bool withColor) const;

    float cellSize() const { return m_cell; }
    std::size_t memoryBytes() const {
        return m_start.size() * sizeof(std::uint32_t) + 7 * m_spheres.size() * sizeof(float);
    }
    static constexpr std::size_t kMaxCells = std::size_t{1} << 23;

  private:
    float m_cell = 1.0f, m_inverse = 1.0f;
    std::array<float, 3> m_lo{0, 0, 0};
    std::array<int, 3> m_dims{0, 0, 0};
    std::vector<std::uint32_t> m_start; // first sphere of each cell (z fastest), then the count
    PackedSpheres m_spheres;            // in cell order
};

} // namespace faultline::core::detail
