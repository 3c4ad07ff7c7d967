// ExtensionModel: a bonded-sphere (DEM) sandbox stretched at its base until normal faults form,
// the built-in demo. Non-dimensional units: sphere radius 1, sphere mass 1, bond stiffness 1.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace faultline::core {

enum class BreakingStrainLaw { Normal, Weibull };
enum class ModelSize { Small, Medium, Large };

struct ExtensionModelOptions {
    // HCP lattice: spheres along x (columns), close-packed planes along y (layers), rows along z.
    int columns = 250;
    int layers = 4;
    int rows = 60;
    std::uint64_t seed = 1;
    // Each bond's breaking strain (stretch / rest length) is drawn once from this law.
    BreakingStrainLaw law = BreakingStrainLaw::Normal;
    double strainMean = 0.01; // normal law
    double strainSd = 0.002;
    double weibullShape = 6.0; // Weibull law (about the same mean and spread)
    double weibullScale = 0.0108;
    double minBreakingStrain = 0.001; // draws are clamped to at least this
    // Weight of a full column of spheres over the mean bond breaking force: sets gravity, and so
    // how far the model is from cohesion-dominated (tensile cracks) to friction-dominated faults.
    double gravityRatio = 5.0;
    double friction = 0.5;     // Coulomb coefficient of sphere-sphere contacts
    double localDamping = 0.7; // Cundall's non-viscous damping (0..1), for quasi-static runs
    double dashpotRatio = 0.2; // bond and contact dashpots, fraction of critical damping
    double dtFactor = 0.25;    // time step = dtFactor * sqrt(mass / stiffness)
    // Kinematics: the right end plate moves away at `velocity` (radii per time unit) until it
    // moved `extension` x length; the left one stays. The base is split into plates at the
    // `discontinuities` (fractions of the length): each step passes on an equal share of the
    // motion, so a velocity discontinuity sits beneath each and a graben grows above it. With
    // stretchWidth > 0 each step is spread over that width (a rubber sheet) instead.
    double extension = 0.05;
    double velocity = 0.02;
    std::vector<double> discontinuities = {0.3, 0.7};
    double stretchWidth = 0.0;
    // Along strike (y), the discontinuities move by `obliquity` x length from one side of the
    // model to the other: a straight oblique line, or with `segments` >= 2 that many straight
    // steps (en echelon, each step a ramp half a segment wide), so faults nucleate as segments,
    // overlap in relay ramps and link.
    double obliquity = 0.0;
    int segments = 0;
    int settleSteps = 1000; // gravity settling before the extension starts
    int frames = 50;        // frames written: after settling, then evenly through the extension
    int layerBands = 10;    // bands of initial height for the `layer` column
    int threads = 0;        // 0: TBB's default
};

// Throws std::invalid_argument naming the first option out of range.
void validate(const ExtensionModelOptions& options);

// small: ~14k spheres, medium (the section demo): 60k, large: 525k.
ExtensionModelOptions extensionOptionsFor(ModelSize size);

// The 3-D demo: a block 256 x 65 x 69 radii (128 x 40 x 40 = 204,800 spheres), 40 frames, its
// two basal discontinuities oblique (38 radii across the block's width), so the grabens run
// oblique to the extension and their faults change place along strike.
ExtensionModelOptions extensionDemoOptions();

// The dump columns, in order: id type x y z radius strain broken_bonds layer x0 y0 z0.
// type: 1 free sphere, 2 basal (moved with its base plate), 3 end plate (x moved, y z free).
// strain: von Mises shear strain of the neighbourhood since settling; broken_bonds: count of the
// sphere's broken bonds; layer: band of initial row (0 at the base); x0 y0 z0: settled position
// (frame 0).
const std::vector<std::string>& extensionDumpColumns();

class ExtensionModel {
  public:
    explicit ExtensionModel(const ExtensionModelOptions& options);
    ~ExtensionModel();
    ExtensionModel(const ExtensionModel&) = delete;
    ExtensionModel& operator=(const ExtensionModel&) = delete;

    std::size_t sphereCount() const;
    std::size_t bondCount() const; // breakable bonds (pairs of basal spheres excluded)
    std::size_t brokenBondCount() const;
    std::int64_t step() const;               // steps done
    std::int64_t frameStep(int frame) const; // the step at which `frame` is taken
    double timeStep() const;
    double gravity() const;

    // Runs `steps` explicit steps (parallel; results do not depend on the thread count).
    void advance(std::int64_t steps);

    // The current state as a frame with extensionDumpColumns(); timestep = step().
    Frame snapshot() const;

  private:
    struct State;
    std::unique_ptr<State> m;
};

struct ExtensionRunStats {
    std::size_t spheres = 0;
    std::size_t bonds = 0;
    std::size_t brokenBonds = 0;
    std::int64_t steps = 0;
    int frames = 0;
    double simulationSeconds = 0; // stepping only
    double totalSeconds = 0;      // with strain, snapshots and the frame sink
    double stepsPerSecond() const { return simulationSeconds > 0 ? steps / simulationSeconds : 0; }
    double sphereStepsPerSecond() const { return stepsPerSecond() * static_cast<double>(spheres); }
};

struct GenerationCancelled : std::runtime_error {
    GenerationCancelled() : std::runtime_error("generation cancelled") {}
};

// Called with frames in order; `frame` counts from 0.
using FrameSink = std::function<void(const Frame& frame, int index)>;
// Called now and then with the fraction done (0..1); returning false cancels the run
// (GenerationCancelled is thrown).
using ProgressCallback = std::function<bool(double fraction)>;

// The options and figures of a run as JSON text (for the model's side-car file).
std::string describeExtensionRun(const ExtensionModelOptions& options,
                                 const ExtensionRunStats& stats);

ExtensionRunStats runExtensionModel(const ExtensionModelOptions& options, const FrameSink& sink,
                                    const ProgressCallback& progress = {});

} // namespace faultline::core
