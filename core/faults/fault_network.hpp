// Fault networks (internal to candidates.cpp): visible spheres grouped into faults that follow
// their orientation, so faults that cross or end against each other come out apart.
//
// 1. Orientation: each sphere's neighbourhood (spheres within `radius`) is fitted with a plane
//    (PCA); planarity = 1 - l1 / l2 of its covariance eigenvalues. In a section model (thinner
//    than the neighbourhood's diameter) planes contain the thin axis.
// 2. Growth: from the most planar spheres, regions grow over linked spheres (distance below
//    link * (ri + rj)) whose normal lies within `angle` of the region's local normal, a running
//    mean along the growth path: a curved fault turns gradually and stays one region, while the
//    normals that bend from one fault to another where two meet part from it. Spheres of low
//    planarity (junctions, scattered spheres) are not grown through.
// 3. Joining: two regions that face each other within a cell or two are one fault when their
//    facing parts are coplanar (normals within `angle`, and one plane fits both about as well
//    as each alone): a fault cut in two by a crossing fault is joined again.
// 4. Leftovers: spheres reached from a fault over a few links (junctions, low planarity) go to
//    the fault whose surface passes nearest; groups below min_size are dissolved first, and
//    spheres that reach no fault are left out.
// Cost: one neighbourhood scan per sphere (parallel), growth and joining linear in spheres.
#pragma once

#include "core/faults/candidates.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace faultline::core::detail {

struct NetworkGroups {
    std::vector<std::int32_t> groupOfRow; // per frame row: group in [0, groupCount) or -1
    std::size_t groupCount = 0;
};

NetworkGroups faultNetworkGroups(const Frame& frame, std::span<const std::uint8_t> visible,
                                 const CandidateOptions& options);

} // namespace faultline::core::detail
