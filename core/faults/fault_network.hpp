// Fault networks (internal to candidates.cpp): visible spheres grouped into faults that follow
// their orientation, so faults that cross or end against each other come out apart.
//
// 1. Orientation: each sphere's neighbourhood (the spheres within `radius` linked to it) is
//    fitted with a plane (PCA over pooled moments of cells half a radius wide); planarity =
//    1 - l1 / l2 of the covariance eigenvalues. In a section model (thinner than the
//    neighbourhood's diameter) planes contain the thin axis; in 3-D an automatic radius grows
//    to 2.5 times the zones' typical thickness when they are thick.
// 2. Growth: from the most planar spheres, regions grow over linked spheres (distance below
//    link * (ri + rj)) whose normal lies within `angle` of the region's local normal, a running
//    mean along the growth path: a curved fault turns gradually and stays one region, while the
//    normals that bend from one fault to another where two meet part from it. Spheres of low
//    planarity (junctions, scattered spheres) are not grown through.
// 3. Joining: two regions within two cells of each other are one fault when their facing parts
//    are planar, their normals within `angle`, and each part's centroid lies on the other's
//    plane: a fault cut in two by a crossing fault is joined again. Then a region smaller than
//    a neighbour whose spheres mostly lie on larger zones' surfaces (the bisector that
//    crossings produce) is dissolved.
// 4. Leftovers: groups below min_size are dissolved; spheres reached from a group over links
//    join, round by round, the zone whose local mid-plane (the mean offset of its spheres along
//    their normals) they lie within.
// 5. Where no group took the spheres, the regions grown there (at least a third of min_size)
//    take them back and seed groups, which take the zones they lie in by the rule of step 4 (the
//    groups before keep what they held): a noisy band whose regions all stayed below min_size
//    is not lost.
// 6. What is left goes to the nearest surface, every group competing, round by round while
//    spheres are taken; a seeded group that grew diffuse or stayed below min_size is dissolved
//    and its spheres go to the nearest surface again; spheres that reach no group are left out.
//    After step 5, so a V's broad base is shared by its two faults, not taken whole by the
//    first that reached it.
// 7. Linked pieces of the spheres left out that hold min_size and are planar become groups.
// 8. Groups linked to each other whose spheres together form a thin sheet (spread across their
//    plane at most 6 % of the spread along it, in variance), each lying along that plane, are
//    one fault: the segments of one shear band, too far apart in orientation for step 3 (17-25
//    degrees in a Yade shear box), come out as one.
// Cost: one pass over pooled cells for the planes, growth and joining linear in spheres, and
// sampled scans for junctions and leftovers: about 0.25 s per 100k visible spheres on 2 cores.
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
