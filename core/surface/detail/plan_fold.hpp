// Surface planning with inverse kernels (r/d, r/d^2): folds of far spheres.
#pragma once

#include "core/surface/detail/sphere_tree.hpp"
#include "core/surface/metaball_field.hpp"

#include <array>
#include <vector>

namespace faultline::core::detail {

// What a planning cell passes to its eight children for their bounds.
// Spheres far from the cell (at least kFoldRatio half-diagonals from its centre) are folded into
// one quadratic about the centre (their summed value, gradient and Hessian there) plus a bound on
// what the quadratic misses anywhere in the cell (Taylor's remainder, from the kernel's
// largest third derivative between the cell and the sphere). The gradients of spheres on every
// side cancel in the sum, where their separate ranges over the cell would add up. The spheres
// near the cell stay in lists, bounded one by one from their nearest and farthest points of
// each child's box. A child's box lies inside its parent's, so the folded bounds hold for it,
// and children only see the spheres near their parent: the cost of a bound follows the spheres
// near the surface, not the whole set.
struct Fold {
    std::array<double, 3> centre{0, 0, 0};
    double value = 0.0;                  // folded spheres' sum at the centre
    std::array<double, 3> grad{0, 0, 0}; // ... its gradient
    std::array<double, 6> hess{};        // ... and Hessian: xx, yy, zz, xy, xz, yz
    double remainder = 0.0;              // largest |sum - quadratic part| over the cell
    std::vector<float> x, y, z, r;       // spheres not folded
};
// Far means at least this many half-diagonals of the cell from its centre.
inline constexpr double kFoldRatio = 4.0;

// Guaranteed bounds of f over `box` (inside the box the fold was made for): the linear part's
// range over the box (exact at its centre, then the gradient's and the Hessian's reach), the
// remainder, and every sphere left in the lists.
FieldBounds foldBounds(const Fold& fold, const Box& box, int power, float minD2);

// The fold a cell with this box passes to its children: the parent's fold moved to the cell's
// centre, plus the parent's listed spheres that are far from this cell. power: 1 or 2.
Fold foldFor(const Fold& parent, const Box& box, int power, float minD2);

} // namespace faultline::core::detail
