// Index of this file:
// [SECTION] Tuning constants
// [SECTION] Helpers: vectors, region sets, a section's thin axis
// [SECTION] Link graph
// [SECTION] Step 1: each sphere's neighbourhood plane
// [SECTION] Step 2: regions grown from the most planar spheres
// [SECTION] Step 3: coplanar regions facing each other join
// [SECTION] Step 3b: where faults cross
// [SECTION] Steps 4 to 6: leftovers join their zone or the nearest surface
// [SECTION] Step 5: small regions no group took
// [SECTION] Step 7: planar pieces no group reached
// [SECTION] Step 8: segments of one band
// [SECTION] faultNetworkGroups: the steps in order

#include "core/faults/fault_network.hpp"

#include "core/faults/candidates.hpp"
#include "core/faults/plane_fit.hpp"
#include "core/faults/sphere_cells.hpp"
#include "core/util/points_within.hpp"
#include "core/util/union_find.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace faultline::core::detail {

namespace {

//-----------------------------------------------------------------------------
// [SECTION] Tuning constants
//-----------------------------------------------------------------------------

// A sphere is grown through only when its neighbourhood is this planar (1 - l1 / l2).
constexpr float kPlanarityMin = 0.6f;
// The same in a section model, where planarity is that of a band in the section's plane: a
// real run's shear band (4-5 grains thick, as thick as the neighbourhood is wide) reads about
// 0.5-0.7 there, and with 0.6 most of it was left over and joined to the wrong fault
// (issue 37, the LAMMPS graben: candidates 20 degrees off the kinematic faults).
constexpr float kSectionPlanarityMin = 0.5f;
// Fewer neighbours than this within the radius: no orientation (scattered spheres).
constexpr std::uint32_t kMinNeighbours = 8;
// The running normal along a growth path keeps this share of its past at each step.
constexpr float kRefKeep = 0.75f;
// Regions smaller than this take no part in joining, and parts facing each other are fitted
// only with at least this many spheres each.
constexpr std::size_t kMinPiece = 4;
constexpr std::size_t kMinFacing = 12;
// A leftover sphere looks for the nearest surface among at most about this many grouped
// spheres around its cell (an even sample).
constexpr std::size_t kLeftoverSample = 1024;
// Leftovers further than a radius from every group wait for their outer neighbours: at most
// this many rounds of the rule "into the zone a sphere lies in" (steps 4 and 5).
constexpr int kLeftoverRounds = 6;
// The rule "to the nearest surface within the radius" (step 6) repeats while it takes spheres,
// at most this many rounds: a thick band's far end, beyond the radius from the region grown
// along one of its edges, is reached through the spheres the round before took.
constexpr int kNearestRounds = 9;
// Whether a region sits on other zones' surfaces is decided on at most about this many of its
// spheres.
constexpr std::size_t kJunctionSample = 256;
// Where no group took the spheres, regions of at least minSize / kReseedShare spheres seed groups.
constexpr std::size_t kReseedShare = 3;
// Leftovers are reached over links from the groups up to about this many radii away.
constexpr double kLeftoverReach = 3.0;
// The neighbourhood radius is grown to this many times the zones' typical thickness.
constexpr double kRadiusOverThickness = 2.5;
// Step 8: two groups are segments of one band when their spheres are linked at least this many
// times and together spread across their best plane at most this share of their spread along
// their longest axis (variances). Measured on the tests' runs: the Yade shear box's band
// segments 0.017-0.041 and a LAMMPS graben fault's deep and shallow parts 0.039 and 0.054 (one
// fault each); a graben fault with a fragment by the wall 0.072, with the V's floor 0.079; the
// planted networks' faults that cross or end against each other 0.21 and more.
constexpr std::size_t kSegmentLinks = 5;
constexpr double kSegmentFlatness = 0.06;
// And each of the two spreads across their joint plane at most this share of its own spread
// along its longest axis (a small piece at an angle is not taken in by a large one's flatness):
// a segment 35 degrees off the joint plane, about 0.33 (sin^2 35); a fault ending against
// another at 45 degrees or more, 0.5 and more. Measured on the pairs above that are one fault:
// 0.02-0.35 (the LAMMPS fault's shallow part, a blob against its deep part, 0.35).
constexpr double kSegmentShare = 0.4;

//-----------------------------------------------------------------------------
// [SECTION] Helpers: vectors, region sets, a section's thin axis
//-----------------------------------------------------------------------------

using F3 = std::array<float, 3>;

float dotf(const F3& a, const F3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

F3 normalized(const F3& v) {
    const float len = std::sqrt(dotf(v, v));
    return len > 0 ? F3{v[0] / len, v[1] / len, v[2] / len} : F3{0, 0, 1};
}

// Union-find over regions: smaller index as root, deterministic.
using RegionSets = UnionFind;

// The thin axis of a section model, or -1: thinner than the neighbourhood's diameter and than a
// quarter of the model's longest side, so a neighbourhood cannot see a plane's tilt along it.
int thinAxis(const Frame& frame, double radius) {
    int axis = 0;
    double extent[3];
    for (int a = 0; a < 3; ++a)
        extent[a] = double(frame.centreMax()[a]) - frame.centreMin()[a];
    for (int a = 1; a < 3; ++a)
        if (extent[a] < extent[axis])
            axis = a;
    const double longest = std::max({extent[0], extent[1], extent[2]});
    return extent[axis] < 2 * radius && extent[axis] < 0.25 * longest ? axis : -1;
}

struct Graph {
    // Linked spheres (distance below link (ri + rj)) in CSR form over the slots of the link
    // cells: neighbours of slot i are adj[start[i] .. start[i + 1]); component per slot.
    std::vector<std::uint32_t> start, adj;
    std::vector<std::uint32_t> component;
};

//-----------------------------------------------------------------------------
// [SECTION] Link graph
//-----------------------------------------------------------------------------

Graph linkGraph(const SphereCells& cells, double link) {
    const std::size_t n = cells.size();
    Graph g;
    std::vector<std::uint32_t> linkCount(n, 0);
    const std::size_t cellCount = cells.cellCount();
    const std::size_t chunks = std::min<std::size_t>(cellCount, 256);
    std::vector<std::vector<std::uint32_t>> chunkLinks(chunks);
    const float k = float(link);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t chunk) {
        const std::size_t c0 = chunk * cellCount / chunks, c1 = (chunk + 1) * cellCount / chunks;
        std::vector<std::uint32_t>& links = chunkLinks[chunk];
        for (std::size_t c = c0; c < c1; ++c)
            for (std::uint32_t i = cells.cellBegin(c); i < cells.cellEnd(c); ++i)
                cells.forEachNeighbourCell(c, [&](std::size_t other) {
                    for (std::uint32_t j = cells.cellBegin(other); j < cells.cellEnd(other); ++j) {
                        const float dx = cells.x[j] - cells.x[i], dy = cells.y[j] - cells.y[i],
                                    dz = cells.z[j] - cells.z[i];
                        const float limit = k * (cells.r[i] + cells.r[j]);
                        if (j != i && dx * dx + dy * dy + dz * dz < limit * limit) {
                            links.push_back(j);
                            ++linkCount[i];
                        }
                    }
                });
    });
    g.start.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        g.start[i + 1] = g.start[i] + linkCount[i];
    g.adj.reserve(g.start[n]);
    for (auto& links : chunkLinks) { // chunks hold consecutive slots, in order
        g.adj.insert(g.adj.end(), links.begin(), links.end());
        std::vector<std::uint32_t>().swap(links);
    }
    constexpr std::uint32_t kNone = ~0u;
    g.component.assign(n, kNone);
    std::vector<std::uint32_t> stack;
    for (std::uint32_t s = 0, label = 0; s < n; ++s) {
        if (g.component[s] != kNone)
            continue;
        g.component[s] = label;
        stack.assign(1, s);
        while (!stack.empty()) {
            const std::uint32_t i = stack.back();
            stack.pop_back();
            for (std::uint32_t e = g.start[i]; e < g.start[i + 1]; ++e)
                if (g.component[g.adj[e]] == kNone) {
                    g.component[g.adj[e]] = label;
                    stack.push_back(g.adj[e]);
                }
        }
        ++label;
    }
    return g;
}

struct Orientations {
    std::vector<F3> normal;       // per link slot
    std::vector<float> planarity; // per link slot; 0 without an orientation
    std::vector<float> thickness; // per link slot: sqrt(12 l1), the width of an even slab
};

//-----------------------------------------------------------------------------
// [SECTION] Step 1: each sphere's neighbourhood plane
//-----------------------------------------------------------------------------

// Step 1: per sphere, the plane of its neighbourhood: the spheres within `radius` that are
// linked to it through other spheres (so a fault nearby but apart does not tilt it). Spheres are
// pooled in cells a third of the radius wide, one pool per cell and linked component (count,
// mean, scatter); a pool's plane sums the pools whose means lie within the radius of its mean,
// and its spheres take that plane (smoothed at a sixth of the radius on purpose: sphere by
// sphere, the normals that bend at a crossing chain two faults more easily). Work grows with
// pools, not with neighbour pairs.
Orientations orient(const Frame& frame, std::span<const std::uint32_t> rows,
                    std::span<const std::uint32_t> rowToLink,
                    std::span<const std::uint32_t> component, double radius, int thin) {
    const std::size_t n = rows.size();
    Orientations o;
    o.normal.assign(n, F3{0, 0, 1});
    o.planarity.assign(n, 0.0f);
    o.thickness.assign(n, 0.0f);
    constexpr int kCellsPerRadius = 2;
    const SphereCells cells(frame, rows, radius / kCellsPerRadius);

    // Pools: slots of one cell and one component, consecutive after sorting each cell by
    // component (slots within a cell are in id order, kept for ties).
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    auto componentOf = [&](std::uint32_t slot) { return component[rowToLink[cells.row[slot]]]; };
    for (std::size_t c = 0; c < cells.cellCount(); ++c)
        std::stable_sort(
            order.begin() + cells.cellBegin(c), order.begin() + cells.cellEnd(c),
            [&](std::uint32_t a, std::uint32_t b) { return componentOf(a) < componentOf(b); });
    struct Pool {
        std::uint32_t begin = 0, end = 0; // into `order`
        std::uint32_t component = 0;
        double count = 0;
        double mean[3] = {0, 0, 0};
        double scatter[6] = {0, 0, 0, 0, 0, 0}; // xx xy xz yy yz zz about the mean
    };
    std::vector<Pool> pools;
    std::vector<std::uint32_t> cellPools(cells.cellCount() + 1, 0);
    for (std::size_t c = 0; c < cells.cellCount(); ++c) {
        cellPools[c] = static_cast<std::uint32_t>(pools.size());
        for (std::uint32_t k = cells.cellBegin(c); k < cells.cellEnd(c);) {
            Pool p;
            p.begin = k;
            p.component = componentOf(order[k]);
            while (k < cells.cellEnd(c) && componentOf(order[k]) == p.component)
                ++k;
            p.end = k;
            pools.push_back(p);
        }
    }
    cellPools[cells.cellCount()] = static_cast<std::uint32_t>(pools.size());
    tbb::parallel_for(std::size_t(0), pools.size(), [&](std::size_t q) {
        Pool& p = pools[q];
        p.count = double(p.end - p.begin);
        for (std::uint32_t k = p.begin; k < p.end; ++k) {
            const std::uint32_t i = order[k];
            p.mean[0] += cells.x[i], p.mean[1] += cells.y[i], p.mean[2] += cells.z[i];
        }
        for (double& m : p.mean)
            m /= p.count;
        for (std::uint32_t k = p.begin; k < p.end; ++k) {
            const std::uint32_t i = order[k];
            const double d[3] = {cells.x[i] - p.mean[0], cells.y[i] - p.mean[1],
                                 cells.z[i] - p.mean[2]};
            p.scatter[0] += d[0] * d[0], p.scatter[1] += d[0] * d[1], p.scatter[2] += d[0] * d[2];
            p.scatter[3] += d[1] * d[1], p.scatter[4] += d[1] * d[2], p.scatter[5] += d[2] * d[2];
        }
    });

    const double r2 = radius * radius;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, cells.cellCount(), 8), [&](const auto& range) {
            std::vector<std::uint32_t> near; // pools of the cells around
            for (std::size_t c = range.begin(); c != range.end(); ++c) {
                near.clear();
                cells.forEachNeighbourCell(
                    c,
                    [&](std::size_t other) {
                        for (std::uint32_t q = cellPools[other]; q < cellPools[other + 1]; ++q)
                            near.push_back(q);
                    },
                    kCellsPerRadius + 1);
                for (std::uint32_t q = cellPools[c]; q < cellPools[c + 1]; ++q) {
                    const Pool& p = pools[q];
                    double count = 0, m[3] = {0, 0, 0}, s[6] = {0, 0, 0, 0, 0, 0};
                    for (std::uint32_t e : near) {
                        const Pool& other = pools[e];
                        if (other.component != p.component)
                            continue;
                        const double d[3] = {other.mean[0] - p.mean[0], other.mean[1] - p.mean[1],
                                             other.mean[2] - p.mean[2]};
                        if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > r2)
                            continue;
                        const double w = other.count;
                        count += w;
                        m[0] += w * d[0], m[1] += w * d[1], m[2] += w * d[2];
                        s[0] += other.scatter[0] + w * d[0] * d[0];
                        s[1] += other.scatter[1] + w * d[0] * d[1];
                        s[2] += other.scatter[2] + w * d[0] * d[2];
                        s[3] += other.scatter[3] + w * d[1] * d[1];
                        s[4] += other.scatter[4] + w * d[1] * d[2];
                        s[5] += other.scatter[5] + w * d[2] * d[2];
                    }
                    if (count < kMinNeighbours)
                        continue;
                    const double inv = 1.0 / count;
                    const double mx = m[0] * inv, my = m[1] * inv, mz = m[2] * inv;
                    Mat3d cov{{{s[0] * inv - mx * mx, s[1] * inv - mx * my, s[2] * inv - mx * mz},
                               {0, s[3] * inv - my * my, s[4] * inv - my * mz},
                               {0, 0, s[5] * inv - mz * mz}}};
                    cov[1][0] = cov[0][1], cov[2][0] = cov[0][2], cov[2][1] = cov[1][2];
                    if (thin >=
                        0) { // the plane contains the thin axis: its normal has no part along it
                        const double big = 1e3 * (cov[0][0] + cov[1][1] + cov[2][2] + 1.0);
                        for (int a = 0; a < 3; ++a)
                            cov[thin][a] = cov[a][thin] = 0;
                        cov[thin][thin] = big;
                    }
                    const SymmetricEigen3 e = eigenSymmetric3(cov);
                    if (!(e.values[1] > 0))
                        continue;
                    const float planarity = float(1.0 - std::max(0.0, e.values[0]) / e.values[1]);
                    const float thickness = float(std::sqrt(12.0 * std::max(0.0, e.values[0])));
                    const F3 normal = normalized(
                        F3{float(e.vectors[0][0]), float(e.vectors[0][1]), float(e.vectors[0][2])});
                    for (std::uint32_t k = p.begin; k < p.end; ++k) {
                        const std::uint32_t li = rowToLink[cells.row[order[k]]];
                        o.planarity[li] = planarity;
                        o.thickness[li] = thickness;
                        o.normal[li] = normal;
                    }
                }
            }
        });
    return o;
}

//-----------------------------------------------------------------------------
// [SECTION] Step 2: regions grown from the most planar spheres
//-----------------------------------------------------------------------------

// Step 2: regions grown from the most planar spheres. Per slot its region or -1, and the
// running normal it was admitted with.
std::size_t grow(const Graph& g, const Orientations& o, double angle, float planarityMin,
                 std::vector<std::int32_t>& region, std::vector<F3>& ref) {
    const std::size_t n = o.normal.size();
    region.assign(n, -1);
    ref = o.normal;
    std::vector<std::uint32_t> seeds;
    for (std::uint32_t i = 0; i < n; ++i)
        if (o.planarity[i] >= planarityMin)
            seeds.push_back(i);
    std::stable_sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) {
        return o.planarity[a] > o.planarity[b];
    });
    const float cosTol = float(std::cos(angle * std::numbers::pi / 180.0));
    std::vector<std::uint32_t> queue;
    std::int32_t regions = 0;
    for (std::uint32_t s : seeds) {
        if (region[s] >= 0)
            continue;
        const std::int32_t label = regions++;
        region[s] = label;
        queue.assign(1, s);
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const std::uint32_t i = queue[head];
            const F3 ri = ref[i];
            for (std::uint32_t e = g.start[i]; e < g.start[i + 1]; ++e) {
                const std::uint32_t j = g.adj[e];
                if (region[j] >= 0 || o.planarity[j] < planarityMin)
                    continue;
                const float c = dotf(o.normal[j], ri);
                if (std::fabs(c) < cosTol)
                    continue;
                const float sign = c < 0 ? -1.0f : 1.0f;
                region[j] = label;
                ref[j] = normalized(F3{kRefKeep * ri[0] + (1 - kRefKeep) * sign * o.normal[j][0],
                                       kRefKeep * ri[1] + (1 - kRefKeep) * sign * o.normal[j][1],
                                       kRefKeep * ri[2] + (1 - kRefKeep) * sign * o.normal[j][2]});
                queue.push_back(j);
            }
        }
    }
    return static_cast<std::size_t>(regions);
}

//-----------------------------------------------------------------------------
// [SECTION] Step 3: coplanar regions facing each other join
//-----------------------------------------------------------------------------

// How far from the midpoint of two parts' centroids their planes (unit normals na, nb, cosine c
// between them) meet: the point of the planes' common line nearest that midpoint; d is the second
// centroid less the first. Infinity for planes too close to parallel.
double bendFromMiddle(const Vec3d& na, const Vec3d& nb, double c, const Vec3d& d) {
    const double det = 1.0 - c * c;
    if (det < 1e-3)
        return INFINITY;
    // The point m + alpha na + beta nb on both planes, m the midpoint: each centroid lies half of
    // d from it.
    const double ra = -0.5 * (na[0] * d[0] + na[1] * d[1] + na[2] * d[2]);
    const double rb = 0.5 * (nb[0] * d[0] + nb[1] * d[1] + nb[2] * d[2]);
    const double alpha = (ra - c * rb) / det, beta = (rb - c * ra) / det;
    return std::sqrt(std::max(0.0, alpha * alpha + beta * beta + 2.0 * alpha * beta * c));
}

// Step 3: regions that face each other and are coplanar there become one group.
// Regions are per link slot; the wide cells find who faces whom.
void join(const SphereCells& cells, std::span<const std::uint32_t> wideToLink,
          std::vector<std::int32_t>& linkRegion, std::size_t regionCount, double angle,
          double meanRadius, int thin) {
    const std::size_t n = cells.size();
    std::vector<std::int32_t> region(n);
    for (std::size_t i = 0; i < n; ++i)
        region[i] = linkRegion[wideToLink[i]];
    std::vector<std::size_t> size(regionCount, 0);
    for (std::int32_t g : region)
        if (g >= 0)
            ++size[std::size_t(g)];
    // Regions of each cell (sorted), and cells of each region.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> cellRegion; // (cell, region)
    for (std::uint32_t i = 0; i < n; ++i)
        if (region[i] >= 0 && size[std::size_t(region[i])] >= kMinPiece)
            cellRegion.emplace_back(cells.cellOf(i), std::uint32_t(region[i]));
    std::sort(cellRegion.begin(), cellRegion.end());
    cellRegion.erase(std::unique(cellRegion.begin(), cellRegion.end()), cellRegion.end());
    std::vector<std::uint32_t> cellStart(cells.cellCount() + 1, 0);
    for (const auto& [c, g] : cellRegion)
        ++cellStart[c + 1];
    for (std::size_t c = 0; c < cells.cellCount(); ++c)
        cellStart[c + 1] += cellStart[c];
    auto regionsOf = [&](std::size_t c) {
        return std::span(cellRegion.data() + cellStart[c], cellRegion.data() + cellStart[c + 1]);
    };
    auto cellHas = [&](std::size_t c, std::uint32_t g) {
        const auto rs = regionsOf(c);
        return std::binary_search(rs.begin(), rs.end(), std::pair{std::uint32_t(c), g});
    };
    std::vector<std::vector<std::uint32_t>> cellsOfRegion(regionCount);
    for (const auto& [c, g] : cellRegion)
        cellsOfRegion[g].push_back(c);

    // Regions within two cells (two to three neighbourhood radii) of each other: a crossing
    // fault's zone and the unsettled spheres on both sides of it fit in that gap.
    constexpr int kReach = 2;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::size_t c = 0; c < cells.cellCount(); ++c)
        cells.forEachNeighbourCell(
            c,
            [&](std::size_t other) {
                if (other < c)
                    return;
                for (const auto& [c1, a] : regionsOf(c))
                    for (const auto& [c2, b] : regionsOf(other))
                        if (a != b)
                            pairs.emplace_back(std::min(a, b), std::max(a, b));
            },
            kReach);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

    // The part of region a in cells within reach of a cell of region b.
    auto facing = [&](std::uint32_t a, std::uint32_t b) {
        std::vector<Vec3d> points;
        for (std::uint32_t c : cellsOfRegion[a]) {
            bool near = false;
            cells.forEachNeighbourCell(
                c, [&](std::size_t other) { near = near || cellHas(other, b); }, kReach);
            if (!near)
                continue;
            for (std::uint32_t i = cells.cellBegin(c); i < cells.cellEnd(c); ++i)
                if (region[i] == std::int32_t(a))
                    points.push_back({cells.x[i], cells.y[i], cells.z[i]});
        }
        return points;
    };
    const double cosTol = std::cos(angle * std::numbers::pi / 180.0);
    std::vector<std::uint8_t> joins(pairs.size(), 0);
    tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t p) {
        const auto [a, b] = pairs[p];
        std::vector<Vec3d> pa = facing(a, b), pb = facing(b, a);
        if (pa.size() < kMinFacing || pb.size() < kMinFacing)
            return;
        const PlaneFit fa = fitPlane(pa, thin), fb = fitPlane(pb, thin);
        auto planar = [](const PlaneFit& f) {
            return f.valid &&
                   std::max(f.eigenvalues[0], 0.0) <= (1.0 - kPlanarityMin) * f.eigenvalues[1];
        };
        if (!planar(fa) || !planar(fb))
            return;
        const double c =
            fa.normal[0] * fb.normal[0] + fa.normal[1] * fb.normal[1] + fa.normal[2] * fb.normal[2];
        if (std::fabs(c) < cosTol)
            return;
        // Aligned: each part's centroid lies on the other's plane, within the parts' own
        // spread (a fault offset a little by the one that cuts it still joins).
        const double spread = std::sqrt(std::max({fa.eigenvalues[0], fb.eigenvalues[0], 0.0}));
        const double tolerance = 1.5 * spread + meanRadius;
        const Vec3d d{fb.centroid[0] - fa.centroid[0], fb.centroid[1] - fa.centroid[1],
                      fb.centroid[2] - fa.centroid[2]};
        const double offA =
            std::fabs(fa.normal[0] * d[0] + fa.normal[1] * d[1] + fa.normal[2] * d[2]);
        const double offB =
            std::fabs(fb.normal[0] * d[0] + fb.normal[1] * d[1] + fb.normal[2] * d[2]);
        // Or one bent fault (listric, or bowed), split where its middle strains less: the parts'
        // planes meet between their centroids. Issue 37, the LAMMPS graben's west-dipping fault
        // at the 92nd percentile of its strain: a steep deep part and a flatter shallow part
        // 18 degrees apart, whose planes meet 3.1 from the midpoint of centroids 10.5 apart.
        // Parallel parts side by side or stepped meet far off, or never.
        const double gap = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (std::max(offA, offB) <= tolerance ||
            bendFromMiddle(fa.normal, fb.normal, c, d) <= 0.5 * gap)
            joins[p] = 1;
    });
    RegionSets sets(regionCount);
    for (std::size_t p = 0; p < pairs.size(); ++p)
        if (joins[p])
            sets.unite(pairs[p].first, pairs[p].second);
    for (std::int32_t& g : linkRegion)
        if (g >= 0)
            g = std::int32_t(sets.find(std::uint32_t(g)));
}

//-----------------------------------------------------------------------------
// [SECTION] Step 3b: where faults cross
//-----------------------------------------------------------------------------

// Step 3b: where faults cross, the spheres of both zones can look like a plane of their own
// (the bisector of the two). Such a region is smaller than a fault next to it and most of its
// spheres lie on that fault's surfaces: it is dissolved, and its spheres are left over.
void dissolveJunctionRegions(const SphereCells& cells, std::span<const std::uint32_t> wideToLink,
                             std::vector<std::int32_t>& linkRegion, const std::vector<F3>& linkRef,
                             std::size_t regionCount, double radius, double onSurface) {
    const std::size_t n = cells.size();
    std::vector<std::int32_t> region(n);
    std::vector<F3> ref(n);
    std::vector<std::size_t> size(regionCount, 0);
    for (std::size_t i = 0; i < n; ++i) {
        region[i] = linkRegion[wideToLink[i]];
        ref[i] = linkRef[wideToLink[i]];
        if (region[i] >= 0)
            ++size[std::size_t(region[i])];
    }
    // Regions with a neighbour (within one cell) more than twice their size.
    std::vector<std::uint8_t> suspect(regionCount, 0);
    for (std::size_t c = 0; c < cells.cellCount(); ++c) {
        std::size_t largest = 0;
        cells.forEachNeighbourCell(c, [&](std::size_t other) {
            for (std::uint32_t j = cells.cellBegin(other); j < cells.cellEnd(other); ++j)
                if (region[j] >= 0)
                    largest = std::max(largest, size[std::size_t(region[j])]);
        });
        for (std::uint32_t i = cells.cellBegin(c); i < cells.cellEnd(c); ++i)
            if (region[i] >= 0 && 2 * size[std::size_t(region[i])] < largest)
                suspect[std::size_t(region[i])] = 1;
    }
    // An even sample of each suspect region's spheres decides (the share is what counts).
    std::vector<std::size_t> stride(regionCount, 1), seen(regionCount, 0), sampled(regionCount, 0);
    for (std::size_t g = 0; g < regionCount; ++g)
        stride[g] = std::max<std::size_t>(1, size[g] / kJunctionSample);
    std::vector<std::uint32_t> slots;
    for (std::uint32_t i = 0; i < n; ++i)
        if (const std::int32_t g = region[i];
            g >= 0 && suspect[std::size_t(g)] &&
            seen[std::size_t(g)]++ % stride[std::size_t(g)] == 0) {
            slots.push_back(i);
            ++sampled[std::size_t(g)];
        }
    if (slots.empty())
        return;
    // The zones' own spheres can stand back from a crossing by a neighbourhood or more (the
    // unsettled band): look two radii out along their tangent planes.
    constexpr int kJunctionReach = 2;
    const float r2 = float(4 * radius * radius), tol = float(onSurface);
    std::vector<std::uint8_t> explained(slots.size(), 0);
    tbb::parallel_for(std::size_t(0), slots.size(), [&](std::size_t q) {
        const std::uint32_t i = slots[q];
        const std::int32_t own = region[i];
        bool found = false;
        cells.forEachNeighbourCell(
            cells.cellOf(i),
            [&](std::size_t other) {
                for (std::uint32_t j = cells.cellBegin(other); j < cells.cellEnd(other) && !found;
                     ++j) {
                    const std::int32_t g = region[j];
                    if (g < 0 || g == own || size[std::size_t(g)] <= size[std::size_t(own)])
                        continue;
                    const F3 d{cells.x[i] - cells.x[j], cells.y[i] - cells.y[j],
                               cells.z[i] - cells.z[j]};
                    found = dotf(d, d) <= r2 && std::fabs(dotf(ref[j], d)) <= tol;
                }
            },
            kJunctionReach);
        explained[q] = found;
    });
    std::vector<std::size_t> onOthers(regionCount, 0);
    for (std::size_t q = 0; q < slots.size(); ++q)
        onOthers[std::size_t(region[slots[q]])] += explained[q];
    for (std::int32_t& g : linkRegion)
        if (g >= 0 && suspect[std::size_t(g)] &&
            2 * onOthers[std::size_t(g)] > sampled[std::size_t(g)])
            g = -1;
}

//-----------------------------------------------------------------------------
// [SECTION] Steps 4 to 6: leftovers join their zone or the nearest surface
//-----------------------------------------------------------------------------

// How leftovers are taken: only into a zone they lie in (the zone's local mid-plane within a
// half-thickness: steps 4 and 5), or by the nearest surface within the radius (step 6).
enum class LeftoverRule { InZone, Nearest };

// Steps 4 to 6: spheres a few links from a group go to the group whose surface passes nearest,
// by `rule`. Everything per link slot; the wide cells find the grouped spheres within the
// radius. Each sphere taken gets, in `ref`, the normal of the grouped sphere that decided.
// `from` (sorted labels; empty: every group): only spheres a few links from those groups are
// taken, and only into them; every group competes for the spheres, and one whose surface passes
// nearer another group stays out, so the other groups keep what they held (step 5). `only` (per
// link slot; empty: every sphere): only those spheres are taken (step 6's second pass).
void assignLeftovers(const SphereCells& wide, std::span<const std::uint32_t> wideToLink,
                     std::span<const std::uint32_t> linkToWide, const Graph& g,
                     std::vector<F3>& ref, std::vector<std::int32_t>& group, double radius,
                     double meanRadius, double onSurface, LeftoverRule rule,
                     std::span<const std::int32_t> from = {},
                     std::span<const std::uint8_t> only = {}) {
    const std::size_t n = wide.size();
    const int hops =
        int(std::clamp(std::ceil(kLeftoverReach * radius / (2 * meanRadius)), 2.0, 192.0));
    std::vector<std::uint8_t> reached(n, 0);
    std::vector<std::uint32_t> frontier, next, left;
    for (std::uint32_t i = 0; i < n; ++i)
        if (group[i] >= 0) {
            reached[i] = 1;
            if (from.empty() || std::binary_search(from.begin(), from.end(), group[i]))
                frontier.push_back(i);
        }
    for (int h = 0; h < hops && !frontier.empty(); ++h) {
        next.clear();
        for (std::uint32_t i : frontier)
            for (std::uint32_t e = g.start[i]; e < g.start[i + 1]; ++e)
                if (const std::uint32_t j = g.adj[e]; !reached[j]) {
                    reached[j] = 1;
                    next.push_back(j);
                    left.push_back(j);
                }
        frontier.swap(next);
    }
    if (!only.empty())
        std::erase_if(left, [&](std::uint32_t j) { return !only[j]; });
    std::vector<std::int32_t> wideGroup(n);
    std::vector<F3> wideRef(n);
    for (std::size_t i = 0; i < n; ++i) {
        wideGroup[i] = group[wideToLink[i]];
        wideRef[i] = ref[wideToLink[i]];
    }
    // Per wide cell, the grouped spheres around it gathered once (sampled evenly past a few
    // thousand), then each leftover of the cell measures its distance to each group's local
    // mid-plane: the mean signed offset from the group's spheres along their normals (a zone's
    // spheres lie on both sides of its mid-plane, so the mean finds the middle of a thick zone).
    // Rounds: spheres further in take the groups their outer neighbours took, with the normal
    // of the sphere that decided.
    std::vector<std::uint32_t> leftWide(left.size());
    for (std::size_t q = 0; q < left.size(); ++q)
        leftWide[q] = linkToWide[left[q]];
    const float r2 = float(radius * radius);
    std::vector<std::int32_t> chosen(left.size(), -1);
    std::vector<F3> chosenRef(left.size());
    std::vector<std::uint32_t> open(left.size());
    std::iota(open.begin(), open.end(), 0u);
    // InZone takes a sphere only into a zone it lies in (mid-plane within a half-thickness):
    // where one zone's settled spheres stand back from a crossing, the other zone's would
    // otherwise take its spheres first. Nearest takes what is left by nearest surface.
    const bool nearest = rule == LeftoverRule::Nearest;
    const float within = float(onSurface);
    // A leftover's verdict depends only on the grouped spheres in the cells around it: after the
    // first round, cells with no newly grouped sphere around them give the same verdict and are
    // skipped (the demo's leftovers took 64% of a fault-following run re-measuring unchanged
    // neighbourhoods).
    std::vector<std::uint8_t> changed(wide.cellCount(), 1);
    const int rounds = nearest ? kNearestRounds : kLeftoverRounds;
    for (int round = 0; round < rounds && !open.empty(); ++round) {
        const bool everyCell = round == 0;
        std::sort(open.begin(), open.end(), [&](std::uint32_t a, std::uint32_t b) {
            return leftWide[a] < leftWide[b]; // wide slots are in cell order
        });
        std::vector<std::pair<std::uint32_t, std::uint32_t>> runs; // [begin, end) of one cell
        for (std::uint32_t k = 0; k < open.size();) {
            const std::uint32_t c = wide.cellOf(leftWide[open[k]]);
            std::uint32_t e = k;
            while (e < open.size() && wide.cellOf(leftWide[open[e]]) == c)
                ++e;
            runs.emplace_back(k, e);
            k = e;
        }
        tbb::parallel_for(std::size_t(0), runs.size(), [&](std::size_t run) {
            const auto [k0, k1] = runs[run];
            if (!everyCell) {
                bool any = false;
                wide.forEachNeighbourCell(wide.cellOf(leftWide[open[k0]]),
                                          [&](std::size_t other) { any = any || changed[other]; });
                if (!any)
                    return;
            }
            std::vector<std::uint32_t> near;
            wide.forEachNeighbourCell(wide.cellOf(leftWide[open[k0]]), [&](std::size_t other) {
                for (std::uint32_t j = wide.cellBegin(other); j < wide.cellEnd(other); ++j)
                    if (wideGroup[j] >= 0)
                        near.push_back(j);
            });
            const std::size_t stride = std::max<std::size_t>(1, near.size() / kLeftoverSample);
            // The sample as arrays, so the distances to all of it are one vectorised loop and
            // only the spheres within reach are visited, in the sample's order.
            std::vector<std::uint32_t> sample;
            for (std::size_t t = 0; t < near.size(); t += stride)
                sample.push_back(near[t]);
            // (Eight more of each: pointsWithin works on whole vectors.)
            const std::size_t m = sample.size();
            std::vector<float> sxv(m + 8), syv(m + 8), szv(m + 8), d2v(m + 8);
            std::vector<std::uint32_t> reachable(m + 8);
            for (std::size_t t = 0; t < m; ++t)
                sxv[t] = wide.x[sample[t]], syv[t] = wide.y[sample[t]], szv[t] = wide.z[sample[t]];
            const float* __restrict sx = sxv.data();
            const float* __restrict sy = syv.data();
            const float* __restrict sz = szv.data();
            const float* d2s = d2v.data(); // written by pointsWithin
            const std::uint32_t* inReach = reachable.data();
            constexpr int kMaxGroups = 8;
            for (std::uint32_t k = k0; k < k1; ++k) {
                const std::uint32_t q = open[k], u = leftWide[q];
                struct Near {
                    std::int32_t group;
                    F3 normal; // the first sphere's, to give the others' normals one sign
                    float offset, count, nearest;
                    std::uint32_t closest; // the nearest sphere, whose normal the leftover takes
                } seen[kMaxGroups];
                int groups = 0;
                const float ux = wide.x[u], uy = wide.y[u], uz = wide.z[u];
                // The sample within reach, in order.
                const std::size_t reach =
                    pointsWithin(sx, sy, sz, m, ux, uy, uz, r2, d2v.data(), reachable.data());
                for (std::size_t i = 0; i < reach; ++i) {
                    const std::size_t t = inReach[i];
                    const std::uint32_t j = sample[t];
                    const F3 d{ux - sx[t], uy - sy[t], uz - sz[t]};
                    const float d2 = d2s[t];
                    const std::int32_t gj = wideGroup[j];
                    int slot = 0;
                    while (slot < groups && seen[slot].group != gj)
                        ++slot;
                    if (slot == groups) {
                        if (groups == kMaxGroups)
                            continue;
                        seen[groups++] = {gj, wideRef[j], 0, 0, d2, j};
                    }
                    Near& s = seen[slot];
                    const float sign = dotf(wideRef[j], s.normal) < 0 ? -1.0f : 1.0f;
                    s.offset += sign * dotf(wideRef[j], d);
                    s.count += 1;
                    if (d2 < s.nearest)
                        s.nearest = d2, s.closest = j;
                }
                float best = 0;
                int pick = -1;
                for (int m = 0; m < groups; ++m) {
                    const float score = std::fabs(seen[m].offset / seen[m].count) +
                                        0.1f * std::sqrt(seen[m].nearest);
                    if (pick < 0 || score < best ||
                        (score == best && seen[m].group < seen[pick].group))
                        best = score, pick = m;
                }
                if (pick >= 0 &&
                    (nearest || std::fabs(seen[pick].offset / seen[pick].count) <= within)) {
                    chosen[q] = seen[pick].group;
                    chosenRef[q] = wideRef[seen[pick].closest];
                }
            }
        });
        std::vector<std::uint32_t> still;
        std::fill(changed.begin(), changed.end(), 0);
        for (std::uint32_t q : open) {
            if (chosen[q] >= 0) {
                wideGroup[leftWide[q]] = chosen[q];
                wideRef[leftWide[q]] = chosenRef[q];
                changed[wide.cellOf(leftWide[q])] = 1;
            } else {
                still.push_back(q);
            }
        }
        if (still.size() == open.size())
            break; // nothing moved: no further round would
        open.swap(still);
    }
    for (std::size_t q = 0; q < left.size(); ++q)
        if (chosen[q] >= 0 &&
            (from.empty() || std::binary_search(from.begin(), from.end(), chosen[q]))) {
            group[left[q]] = chosen[q];
            ref[left[q]] = chosenRef[q];
        }
}

//-----------------------------------------------------------------------------
// [SECTION] Step 5: small regions no group took
//-----------------------------------------------------------------------------

// Step 5: spheres still in no group go back to the region they grew in when that region, as
// grown, held minSize / kReseedShare spheres or more (rounded down); the in-zone rule of step 4
// then runs again over the spheres a few links from those regions, with every group competing
// for them, but what it gives to the groups of the steps before is taken back (they keep what
// they held). The seeded groups then take part in step 6 like the others; one that grew diffuse
// or stayed below minSize is dissolved there (dissolveSeeded). Where every region grown in a
// noisy band stays below minSize, all of them were dissolved, no group took their spheres, and
// the band with its strained surroundings is diffuse, not a planar piece: the whole of it had no
// candidate (issue 37: a Yade sandbox's V of two normal faults at the 85th and 86th percentile
// of incremental strain). Seeded before step 6, not after it: the fault whose regions all stayed
// small competes for the V's broad base with the one that reached it (the floored Yade
// sandbox's 75-degree fault had taken all of it, and read 61 degrees at the 90th percentile).
// Returns the labels of the regions given back, which no group had.
std::vector<std::int32_t> reseedUntaken(std::span<const std::int32_t> grown,
                                        std::span<const std::size_t> size, std::size_t minSize,
                                        std::vector<std::int32_t>& group) {
    const std::size_t least = std::max<std::size_t>(1, minSize / kReseedShare);
    std::vector<std::uint8_t> given(size.size(), 0);
    for (std::size_t i = 0; i < group.size(); ++i)
        if (group[i] == -1 && grown[i] >= 0 && size[std::size_t(grown[i])] >= least) {
            group[i] = grown[i]; // a region below minSize: its label is no group's
            given[std::size_t(grown[i])] = 1;
        }
    std::vector<std::int32_t> seeded;
    for (std::size_t r = 0; r < given.size(); ++r)
        if (given[r])
            seeded.push_back(std::int32_t(r));
    return seeded;
}

// The groups `seeded` that grew diffuse (a blob of distributed strain, as candidateShape judges
// it) are dissolved, step 5 being for bands as step 7 is, and so are those still below minSize,
// which would be dropped with their spheres. Per link slot, whether its sphere was released
// (empty: none was).
std::vector<std::uint8_t> dissolveSeeded(const Frame& frame, const SphereCells& linkCells,
                                         std::span<const std::int32_t> seeded, std::size_t minSize,
                                         std::vector<std::int32_t>& group) {
    std::vector<std::vector<std::int64_t>> ids(seeded.size());
    for (std::size_t i = 0; i < group.size(); ++i)
        if (const auto at = std::lower_bound(seeded.begin(), seeded.end(), group[i]);
            at != seeded.end() && *at == group[i])
            ids[std::size_t(at - seeded.begin())].push_back(frame.ids[linkCells.row[i]]);
    std::vector<std::uint8_t> drop(seeded.size(), 0);
    for (std::size_t k = 0; k < seeded.size(); ++k) {
        if (ids[k].empty())
            continue;
        if (ids[k].size() < minSize) {
            drop[k] = 1;
        } else {
            const CandidateShape shape = candidateShape(frame, ids[k]);
            drop[k] = !shape.valid || shape.diffuse;
        }
    }
    if (std::find(drop.begin(), drop.end(), 1) == drop.end())
        return {};
    std::vector<std::uint8_t> released(group.size(), 0);
    for (std::size_t i = 0; i < group.size(); ++i)
        if (const auto at = std::lower_bound(seeded.begin(), seeded.end(), group[i]);
            at != seeded.end() && *at == group[i] && drop[std::size_t(at - seeded.begin())]) {
            group[i] = -1;
            released[i] = 1;
        }
    return released;
}

//-----------------------------------------------------------------------------
// [SECTION] Step 7: planar pieces no group reached
//-----------------------------------------------------------------------------

// Step 7: linked pieces of the spheres still in no group become groups of their own when they
// hold at least minSize spheres and are planar (not diffuse, as candidateShape judges it): a
// band one or two grains thick and ragged grows only regions smaller than minSize, which are
// dissolved, and its spheres lie too far from every group to be leftovers (issue 37: a Yade
// sandbox's 55-degree fault at the 90th percentile of incremental strain had no candidate).
// Returns the number of groups; new ones are numbered from `groups`.
std::size_t planarPieces(const Frame& frame, const SphereCells& linkCells, const Graph& graph,
                         std::size_t minSize, std::size_t groups,
                         std::vector<std::int32_t>& group) {
    constexpr std::int32_t kSeen = -2, kLeft = -3;
    std::vector<std::uint32_t> piece;
    std::vector<std::int64_t> ids;
    for (std::uint32_t s = 0; s < group.size(); ++s) {
        if (group[s] != -1)
            continue;
        piece.assign(1, s);
        group[s] = kSeen;
        for (std::size_t h = 0; h < piece.size(); ++h)
            for (std::uint32_t e = graph.start[piece[h]]; e < graph.start[piece[h] + 1]; ++e)
                if (const std::uint32_t j = graph.adj[e]; group[j] == -1) {
                    group[j] = kSeen;
                    piece.push_back(j);
                }
        bool planar = false;
        if (piece.size() >= minSize) {
            ids.clear();
            for (std::uint32_t j : piece)
                ids.push_back(frame.ids[linkCells.row[j]]);
            const CandidateShape shape = candidateShape(frame, ids);
            planar = shape.valid && !shape.diffuse;
        }
        const std::int32_t label = planar ? std::int32_t(groups++) : kLeft;
        for (std::uint32_t j : piece)
            group[j] = label;
    }
    for (std::int32_t& g : group)
        if (g == kLeft)
            g = -1;
    return groups;
}

//-----------------------------------------------------------------------------
// [SECTION] Step 8: segments of one band
//-----------------------------------------------------------------------------

// Moments of a group's centres: count, sum and sum of outer products (about `origin`, so large
// coordinates keep their precision); the moments of two groups together are their sums.
struct Moments {
    double n = 0;
    Vec3d s{0, 0, 0};
    Mat3d ss{};
    void add(const Vec3d& p) {
        n += 1;
        for (int a = 0; a < 3; ++a) {
            s[a] += p[a];
            for (int b = 0; b < 3; ++b)
                ss[a][b] += p[a] * p[b];
        }
    }
    Moments operator+(const Moments& o) const {
        Moments m = *this;
        m.n += o.n;
        for (int a = 0; a < 3; ++a) {
            m.s[a] += o.s[a];
            for (int b = 0; b < 3; ++b)
                m.ss[a][b] += o.ss[a][b];
        }
        return m;
    }
    Mat3d covariance() const {
        Mat3d c{};
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                c[a][b] = ss[a][b] / n - (s[a] / n) * (s[b] / n);
        return c;
    }
};

// The spread of a set of centres (its covariance) across its best plane and along its longest
// axis, and that plane's unit normal. In a section model (`thin` an axis) the plane contains the
// thin axis: spreads and normal are taken in the section.
struct Spread {
    double across = 0, along = 0;
    Vec3d normal{0, 0, 0};
};
Spread spreadOf(const Mat3d& c, int thin) {
    const SymmetricEigen3 e = planeAxes(c, thin);
    return {std::max(0.0, e.values[0]), thin >= 0 ? e.values[1] : e.values[2], e.vectors[0]};
}

// Whether two linked sets of centres (their moments) are segments of one thin sheet: together
// they spread across their best plane at most kSegmentFlatness of their spread along it, and
// each spreads across that plane at most kSegmentShare of its own length (so a small piece at
// an angle, a fault ending against a large one, is not taken in by the large one's flatness).
bool oneSheet(const Moments& a, const Moments& b, int thin, double tiny) {
    if (a.n < 3 || b.n < 3)
        return false;
    const Moments u = a + b;
    const Spread joint = spreadOf(u.covariance(), thin);
    if (!(joint.along > tiny) || !(joint.across <= kSegmentFlatness * joint.along))
        return false;
    for (const Moments* m : {&a, &b}) {
        const Mat3d c = m->covariance();
        const Vec3d& nn = joint.normal;
        double across = 0, offset = 0;
        for (int p = 0; p < 3; ++p) {
            offset += nn[p] * (m->s[p] / m->n - u.s[p] / u.n);
            for (int q = 0; q < 3; ++q)
                across += nn[p] * c[p][q] * nn[q];
        }
        const double along = spreadOf(c, thin).along;
        if (!(along > tiny) || !(across + offset * offset <= kSegmentShare * along))
            return false;
    }
    return true;
}

// Step 8: groups linked to each other (at least kSegmentLinks links between their spheres) whose
// spheres together form a sheet as thin as kSegmentFlatness, each of them lying along it
// (kSegmentShare), are one fault: a shear band whose segments differ by 17-25 degrees (a Yade
// shear box's band steps from 30 to 5 to 22 degrees), too far apart in orientation for step 3,
// is one band, while two faults meeting at an angle, crossing or ending against each other form
// no thin sheet together and stay apart. Pairs are taken in order, each tested on the sets its
// groups have joined by then: a chain of segments joins only while it stays one thin sheet.
// Returns the group each group joins.
std::vector<std::int32_t> joinSegments(const SphereCells& cells, const Graph& g,
                                       std::span<const std::int32_t> group, std::size_t groupCount,
                                       int thin, double meanRadius) {
    // Spreads below this (squared lengths) are no spread: a set of one point, in rounding.
    const double tiny = 1e-6 * meanRadius * meanRadius;
    std::vector<Moments> moments(groupCount);
    const Vec3d origin{cells.size() ? cells.x[0] : 0.0f, cells.size() ? cells.y[0] : 0.0f,
                       cells.size() ? cells.z[0] : 0.0f};
    for (std::size_t i = 0; i < cells.size(); ++i)
        if (group[i] >= 0)
            moments[std::size_t(group[i])].add(
                {cells.x[i] - origin[0], cells.y[i] - origin[1], cells.z[i] - origin[2]});
    std::vector<std::pair<std::uint32_t, std::uint32_t>> links;
    for (std::uint32_t i = 0; i < cells.size(); ++i)
        for (std::uint32_t e = g.start[i]; e < g.start[i + 1]; ++e)
            if (const std::uint32_t j = g.adj[e];
                i < j && group[i] >= 0 && group[j] >= 0 && group[i] != group[j])
                links.emplace_back(std::uint32_t(std::min(group[i], group[j])),
                                   std::uint32_t(std::max(group[i], group[j])));
    std::sort(links.begin(), links.end());
    // In the pairs' order, each tested on the sets their groups are in by then (a chain of
    // segments is one sheet only if it stays one as it grows).
    UnionFind sets{groupCount};
    for (std::size_t k = 0; k < links.size();) {
        std::size_t e = k;
        while (e < links.size() && links[e] == links[k])
            ++e;
        const std::uint32_t a = sets.find(links[k].first), b = sets.find(links[k].second);
        if (e - k >= kSegmentLinks && a != b && oneSheet(moments[a], moments[b], thin, tiny)) {
            const Moments joined = moments[a] + moments[b];
            sets.unite(a, b);
            moments[sets.find(a)] = joined;
        }
        k = e;
    }
    std::vector<std::int32_t> to(groupCount);
    for (std::size_t q = 0; q < groupCount; ++q)
        to[q] = std::int32_t(sets.find(std::uint32_t(q)));
    return to;
}

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] faultNetworkGroups: the steps in order
//-----------------------------------------------------------------------------

NetworkGroups faultNetworkGroups(const Frame& frame, std::span<const std::uint8_t> visible,
                                 const CandidateOptions& options) {
    NetworkGroups out;
    out.groupOfRow.assign(frame.size(), -1);
    const std::vector<std::uint32_t> rows = linkableRows(frame, visible);
    if (rows.empty())
        return out;
    double rsum = 0, rmax = 0;
    for (std::uint32_t r : rows) {
        rsum += frame.radius[r];
        rmax = std::max(rmax, double(frame.radius[r]));
    }
    const double meanRadius = rsum / double(rows.size());
    double radius = options.radius > 0 ? options.radius : 8.0 * meanRadius;
    if (!(radius > 0) || !(meanRadius > 0) || !std::isfinite(radius) || !std::isfinite(rmax))
        return out; // spheres without size link nothing; sizes beyond floats orient nothing
    const int thin = thinAxis(frame, radius);
    const SphereCells linkCells(frame, rows, options.link * 2.0 * rmax);
    const Graph graph = linkGraph(linkCells, options.link);
    std::vector<std::uint32_t> rowToLink(frame.size());
    for (std::uint32_t i = 0; i < linkCells.size(); ++i)
        rowToLink[linkCells.row[i]] = i;
    // Cells one neighbourhood wide, and their slots' link slots both ways.
    std::vector<std::uint32_t> wideToLink(rows.size()), linkToWide(rows.size());
    auto wideCells = [&](double cell) {
        SphereCells cells(frame, rows, cell);
        for (std::uint32_t i = 0; i < cells.size(); ++i) {
            wideToLink[i] = rowToLink[cells.row[i]];
            linkToWide[wideToLink[i]] = i;
        }
        return cells;
    };
    SphereCells wide = wideCells(radius);

    Orientations o = orient(frame, rows, rowToLink, graph.component, radius, thin);
    double zoneThickness = 2 * meanRadius;
    if (options.radius <= 0 && thin < 0) {
        // Zones thicker than the neighbourhood look barely planar: measure their thickness and
        // look again with a neighbourhood that spans it. Not in sections: there a zone is a
        // band whose roughness reads as thickness, and a wider neighbourhood spans both arms of
        // a graben.
        std::vector<float> t;
        for (std::size_t i = 0; i < o.thickness.size(); ++i)
            if (o.planarity[i] > 0.3f)
                t.push_back(o.thickness[i]);
        if (!t.empty()) {
            std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
            zoneThickness = std::max(zoneThickness, double(t[t.size() / 2]));
            const double wanted = std::min(kRadiusOverThickness * t[t.size() / 2], 3.0 * radius);
            if (wanted > 1.2 * radius) {
                radius = wanted;
                wide = wideCells(radius);
                o = orient(frame, rows, rowToLink, graph.component, radius, thin);
            }
        }
    }
    // A sphere lies on a zone's surface when it is this close to the zone's mid-plane.
    const double onSurface = std::max(0.5 * zoneThickness, 1.5 * meanRadius);
    std::vector<std::int32_t> region;
    std::vector<F3> ref;
    const std::size_t regionCount = grow(
        graph, o, options.angle, thin >= 0 ? kSectionPlanarityMin : kPlanarityMin, region, ref);
    join(wide, wideToLink, region, regionCount, options.angle, meanRadius, thin);
    dissolveJunctionRegions(wide, wideToLink, region, ref, regionCount, radius, onSurface);

    // Groups below min_size are dissolved, so their spheres can join a fault next to them.
    std::vector<std::size_t> size(regionCount, 0);
    for (std::int32_t g : region)
        if (g >= 0)
            ++size[std::size_t(g)];
    const std::size_t minSize = std::max<std::size_t>(options.minSize, 1);
    const std::vector<std::int32_t> grown = region;
    for (std::int32_t& g : region)
        if (g >= 0 && size[std::size_t(g)] < minSize)
            g = -1;
    // Step 4: leftovers join the zone they lie in.
    assignLeftovers(wide, wideToLink, linkToWide, graph, ref, region, radius, meanRadius, onSurface,
                    LeftoverRule::InZone);
    // Step 5: where no group took the spheres, the regions grown there seed groups after all,
    // and take the zones they lie in. Into the seeded groups only: the groups of the steps before
    // keep what they held, and no more.
    const auto seeded = reseedUntaken(grown, size, minSize, region);
    if (!seeded.empty())
        assignLeftovers(wide, wideToLink, linkToWide, graph, ref, region, radius, meanRadius,
                        onSurface, LeftoverRule::InZone, seeded);
    // Step 6: what is left goes to the nearest surface, every group competing (the seeded ones
    // too: a V's broad base is shared by its two faults rather than taken whole by the one
    // that reached it first). A seeded group grown diffuse, or still below minSize, is
    // dissolved, and its spheres alone go to the nearest surface again (a band's deep, broad
    // end, which had seeded a group of its own).
    assignLeftovers(wide, wideToLink, linkToWide, graph, ref, region, radius, meanRadius, onSurface,
                    LeftoverRule::Nearest);
    if (!seeded.empty())
        if (const auto released = dissolveSeeded(frame, linkCells, seeded, minSize, region);
            !released.empty())
            assignLeftovers(wide, wideToLink, linkToWide, graph, ref, region, radius, meanRadius,
                            onSurface, LeftoverRule::Nearest, {}, released);
    // Step 7: planar pieces no group reached are groups of their own.
    const std::size_t groupCount =
        planarPieces(frame, linkCells, graph, minSize, regionCount, region);

    // Step 8: the segments of one band are one fault.
    const std::vector<std::int32_t> joined =
        joinSegments(linkCells, graph, region, groupCount, thin, meanRadius);
    for (std::int32_t& g : region)
        if (g >= 0)
            g = joined[std::size_t(g)];

    std::vector<std::int32_t> dense(groupCount, -1);
    for (std::size_t i = 0; i < linkCells.size(); ++i)
        if (const std::int32_t g = region[i]; g >= 0) {
            if (dense[std::size_t(g)] < 0)
                dense[std::size_t(g)] = std::int32_t(out.groupCount++);
            out.groupOfRow[linkCells.row[i]] = dense[std::size_t(g)];
        }
    return out;
}

} // namespace faultline::core::detail
