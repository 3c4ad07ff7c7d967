// PlanesModel: an HCP block cut by planar fault patches whose answer is known (plane, dip,
// dip direction, member ids per frame), so tests of fault finding can check exact results.
#pragma once

#include "core/model/frame.hpp"
#include "core/synth/extension_model.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace faultline::core {

// A fault patch: a disc in its plane. Orientation as in the journal contract: +x east, +y north,
// +z up; dip in degrees below horizontal (0-90), dip direction the azimuth of steepest descent
// in degrees clockwise from north (0-360).
struct PlaneFaultSpec {
    std::array<double, 3> centre{0, 0, 0};
    double dip = 60;
    double dipDirection = 90;
    double throwLength = 6; // final vertical throw at the centre, in radii
    double radius = 20;     // final radius of the patch in its plane
    double appearsAt = 0;   // fraction of the run (0..1) at which the fault starts to grow
    // Networks. endsAgainst: index of another fault (0-based) this one ends against: members
    // lie only on the side of that fault's surface where this fault's centre lies (a T or Y
    // junction; two faults ending against each other at depth make a V). listricDip: when set,
    // the dip runs from `dip` at the top of the patch to this at its bottom (a listric fault,
    // curved along dip, straight along strike). clip: members only inside [clipLo, clipHi].
    int endsAgainst = -1;
    std::optional<double> listricDip;
    std::array<double, 3> clipLo{-1e300, -1e300, -1e300};
    std::array<double, 3> clipHi{1e300, 1e300, 1e300};
};

struct PlanesModelOptions {
    // HCP block (as makeHcpLattice): spheres along x, close-packed planes along y, rows along z.
    int columns = 40;
    int layers = 30;
    int rows = 28;
    std::uint64_t seed = 1;
    int frames = 10; // frame 0 has no fault; faults grow to full size by the last frame
    // Faults as given; when empty, `faultCount` random ones, with dip, dip direction, centre,
    // throw, size and start drawn from the seed unless fixed below.
    std::vector<PlaneFaultSpec> faults;
    int faultCount = 3;
    std::optional<double> dip;
    std::optional<double> dipDirection;
    std::optional<double> throwLength;
    double halfThickness = 1.5; // a sphere is a member when its centre lies this close to the patch
    double minGap = 6.0;        // random faults keep at least this far apart (zone to zone)
    int layerBands = 10;
    // Scattered spheres that look broken (strain and broken bonds of a zone) but belong to no
    // fault, as a fraction of all spheres.
    double noiseFraction = 0;
};

// small: ~7k spheres, medium: ~34k, large: ~270k.
PlanesModelOptions planesOptionsFor(ModelSize size);

// A fault network in ~154k spheres (128 x 98 x 69 radii): a conjugate pair crossing in an X
// (F1, F2), a fault (F4) ending at depth against another (F3) in a V/Y, a listric fault (F5,
// dip 70 to 30), 0.3% scattered noise spheres; throw 2 radii each.
PlanesModelOptions planesNetworkOptions();

struct PlaneFault {
    std::string name; // F1, F2, ...
    PlaneFaultSpec spec;
    std::array<double, 3> normal{0, 0, 1}; // unit, pointing up (into the hanging wall)
    double strike = 0;                     // dip direction - 90, right-hand rule, 0-360
    double slip = 0;                       // final slip along dip at the centre
    int firstFrame = 0;                    // first frame with members
    // Member ids per frame (sorted): spheres within halfThickness of the plane, inside the
    // patch grown so far.
    std::vector<std::vector<std::int64_t>> members;
};

struct PlanesModel {
    PlanesModelOptions options;
    std::vector<Frame> frames; // columns as extensionDumpColumns()
    std::vector<PlaneFault> faults;
    std::vector<std::int64_t> shared; // ids in two or more faults' final members, sorted
    std::vector<std::int64_t> noise;  // scattered broken spheres in no fault, sorted
};

// Upward unit normal of a plane with this dip and dip direction (degrees).
std::array<double, 3> planeNormal(double dip, double dipDirection);

// Builds the frames in memory. Members get high strain and broken bonds; the hanging wall next
// to each patch slides down-dip (fading out over halfThickness + minGap / 2 from the plane), the
// throw and the patch growing from zero. Throws std::invalid_argument on bad
// options, std::runtime_error when random faults cannot be placed apart in the block.
PlanesModel generatePlanesModel(const PlanesModelOptions& options);

// The ground truth as JSON text: per fault its plane (point, normal), dip, dip_direction,
// strike, throw, slip, radius, ends_against and listric_dip when set, and member ids per frame;
// "shared" (ids of two zones) and "noise" ids.
std::string planesTruthJson(const PlanesModel& model);

struct PlanesModelFiles {
    std::string dump;  // DIR/planes.lammpstrj[.gz]
    std::string truth; // DIR/planes_truth.json
};

// Writes the dump and the truth JSON into `folder` (created when missing).
PlanesModelFiles writePlanesModel(const PlanesModel& model, const std::string& folder, bool gzip);

} // namespace faultline::core
