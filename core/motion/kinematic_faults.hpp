// Kinematic faults: the faults of a run read from how its spheres moved between two frames,
// without trusting any strain threshold (issue 37's "kinematic truth"). The spheres' displacements
// are clustered into rigid blocks; a fault is the boundary between two blocks, its plane fitted
// through the midpoints of neighbouring pairs that belong to different blocks.
//
// Method (matched by id; displacements and pair vectors use the minimum image on periodic axes;
// d = the mean sphere diameter; neighbours: centres closer than cutoff x d in the later frame):
//  1. Seeds: connected pieces of neighbours whose displacements differ by less than
//     max(beta x S, floor x d), S the 90th percentile of |u - median u| (the spread of motion).
//     Pieces of at least max(minBlock, minBlockFraction x N) spheres are blocks.
//  2. Each block's rigid motion, linearised: u = t + w x (p - c), least squares.
//  3. Rounds: every sphere goes to the block whose motion predicts its displacement best; pieces
//     of one block smaller than a block take their neighbours' majority; while more than two
//     blocks remain, the one with the smallest share of interior spheres (no neighbour in another
//     block) is dissolved when that share is under minInterior (slivers of in-between motion
//     inside a fault zone); each block is refitted twice on the spheres it explains within three
//     times its median misfit.
//  4. Fault A|B: midpoints of A-B neighbour pairs where the two motions differ by more than
//     max(4 x the quieter block's median misfit, 0.05 d); a least-squares plane (containing a
//     section model's thin axis), refitted without midpoints beyond trim x its RMS distance.
//     Identifiable: at least 30 midpoints, RMS under 1.5 d, slip over 3 x the rougher block's
//     misfit, and the motion changing from one block's to the other's (10 % to 90 %) within
//     maxWidth d across the plane (a sharp boundary, not a diffusely deforming wedge).
// Use consecutive frames (incremental motion): over a long interval a graben is no rigid block.
#pragma once

#include "core/faults/plane_fit.hpp"
#include "core/model/frame.hpp"

#include <cstdint>
#include <vector>

namespace faultline::core {

struct KinematicOptions {
    double beta = 0.08;        // seed tolerance, of the spread of motion
    double floor = 0.01;       // smallest seed tolerance, mean diameters
    double cutoff = 1.5;       // neighbours, mean diameters
    std::size_t minBlock = 30; // spheres
    double minBlockFraction = 0.005;
    int rounds = 5;
    double minInterior = 0.5;
    double trim = 2.5;
    double maxWidth = 5.0; // identifiable: motion changes within this many mean diameters
};

// u(p) = translation + rotation x (p - centre), in world units.
struct RigidMotion {
    Vec3d centre{}, translation{}, rotation{};
    Vec3d at(const Vec3d& p) const;
};

struct KinematicFault {
    std::size_t blockA = 0, blockB = 0; // blockA < blockB
    std::size_t midpoints = 0;          // after trimming
    std::vector<Vec3d> points;          // those midpoints (later frame's positions)
    PlaneFit plane;                     // through the midpoints
    double rms = 0;                     // midpoints' RMS distance to the plane, world units
    double slip = 0;                    // |motion A - motion B| at the plane's centroid
    double width = 0;                   // 10-90 % width of the change of motion across it
    bool identifiable = false;
};

struct KinematicResult {
    double meanDiameter = 0;
    int sectionAxis = -1; // a section model's thin axis (fault planes contain it), else -1
    std::vector<std::int32_t> blockOfRow; // per row of `after`: block, or -1 (not in `before`)
    std::vector<RigidMotion> blocks;      // largest block first
    std::vector<std::size_t> blockSizes;
    std::vector<double> blockMisfit;    // median |u - predicted|, world units
    std::vector<KinematicFault> faults; // most midpoints first
};

// Throws std::invalid_argument when the frames share fewer than 2 * minBlock ids.
KinematicResult kinematicFaults(const Frame& before, const Frame& after,
                                const KinematicOptions& options = {});

} // namespace faultline::core
