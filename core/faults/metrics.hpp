// Fault metrics per frame: count, extent, best-fit plane (dip, dip direction, strike), thickness,
// area, throw from initial positions, and the seed point where the first bonds broke.
#pragma once

#include "core/faults/fault.hpp"
#include "core/faults/frame_loader.hpp"
#include "core/faults/plane_fit.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct MetricsOptions {
    std::string brokenBondsVariable = "broken_bonds"; // for the seed and the `broken` count
    bool computeThrow = true;
    // Throw samples non-member spheres at plane distances [h, h + slab] on each side, where
    // h = thickness / 2 + gap; gap and slab in mean member diameters.
    double throwGapDiameters = 0.5;
    double throwSlabDiameters = 3.0;
    std::size_t throwMinSamples = 3; // per side
};

enum class ThrowStatus {
    Ok,
    Disabled,       // MetricsOptions::computeThrow is false
    NoDisplacement, // the frame has no x0, y0, z0 columns (nor strain from motion's ref_x...)
    NoPlane,        // the plane is undefined (fewer than 3 members, or a line)
    TooFewSamples,  // fewer than throwMinSamples spheres on one side
};
std::string_view throwStatusName(ThrowStatus status); // ok | disabled | no_displacement | ...

// Definitions (positions are sphere centres; NaN marks "undefined"):
//  count      fault members present in the frame
//  min, max   axis-aligned bounds of the members; centroid their mean
//  plane      PCA fit (plane_fit.hpp): normal = smallest eigenvector, pointing up
//  thickness  sqrt(12) x the standard deviation of member distances to the plane: the width of
//             a uniformly filled slab with the same spread (exact for uniform slabs)
//  area       members projected on the plane into square cells one mean member diameter wide;
//             area = occupied cells x cell area (the footprint, holes and all)
//  length     the footprint's extent along strike (cells from first to last x cell width):
//             the fault's trace length; height its extent down dip
//  throw      slip = mean displacement (x - x0) of hanging-wall samples minus that of footwall
//             samples. The hanging wall is the side the upward normal points to. Samples: spheres
//             not in the fault, at plane distance in [h, h + slab] (MetricsOptions), whose
//             projection falls in an occupied area cell. throwVertical = slip.z (negative: the
//             hanging wall went down, normal sense); netSlip = |slip|; dipSlip = slip . down-dip
//             (positive: normal sense); strikeSlip = slip . strike direction.
//  broken     members with brokenBondsVariable > 0 in this frame; brokenCentroid their mean
struct FaultFrameMetrics {
    std::size_t frame = 0;
    std::size_t fault = 0; // index into the faults given
    std::string name;
    std::size_t count = 0;
    Vec3d min{}, max{}, centroid{};
    bool planeValid = false;
    Vec3d normal{};
    Vec3d eigenvalues{};
    double dip = 0, dipDirection = 0, strike = 0;
    double thickness = 0;
    double area = 0;
    double length = 0, height = 0; // footprint's extent along strike and down dip
    double meanRadius = 0;
    ThrowStatus throwStatus = ThrowStatus::Disabled;
    Vec3d slip{};
    double throwVertical = 0, netSlip = 0, dipSlip = 0, strikeSlip = 0;
    std::size_t hangingWallSamples = 0, footwallSamples = 0;
    std::size_t broken = 0;
    Vec3d brokenCentroid{};
};

// Seed: let t be the earliest frame in which any member present has brokenBondsVariable > 0;
// the seed is the centroid, at frame t, of the members with brokenBondsVariable > 0 at frame t
// (all of which broke first there). Frames without the variable count as having none.
struct FaultSeed {
    bool found = false;
    std::size_t frame = 0;
    std::size_t count = 0;
    Vec3d point{};
};

// Metrics of every fault in one frame (parallel over faults).
std::vector<FaultFrameMetrics> computeFrameMetrics(const Frame& frame, std::size_t frameIndex,
                                                   std::span<const Fault> faults,
                                                   const MetricsOptions& options = {});

struct FaultMetricsSeries {
    std::size_t frameCount = 0;
    std::size_t faultCount = 0;
    std::vector<FaultFrameMetrics> rows; // frame-major: rows[frame * faultCount + fault]
    std::vector<FaultSeed> seeds;        // per fault
    // The frames whose rows were asked for (the CSV writes only these); rows of other frames
    // hold what the seeds needed, or nothing.
    FrameSelection selection;

    const FaultFrameMetrics& at(std::size_t frame, std::size_t fault) const {
        return rows[frame * faultCount + fault];
    }
};

// Frames 0..frameCount-1, or the selected ones (parallel over frames; `load` must be
// thread-safe), and the seeds (from earlier or later frames too when the selection lacks them).
FaultMetricsSeries computeMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        std::span<const Fault> faults,
                                        const MetricsOptions& options = {},
                                        const FrameSelection& selection = {});

// The seeds from already computed rows (frame-major, as in FaultMetricsSeries).
std::vector<FaultSeed> seedsFromRows(std::span<const FaultFrameMetrics> rows,
                                     std::size_t faultCount);

} // namespace faultline::core
