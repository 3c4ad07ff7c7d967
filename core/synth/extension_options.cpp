// Options of the extension model: the preset sizes, their checks and the run description.
#include "core/synth/extension_model.hpp"

#include <nlohmann/json.hpp>

namespace faultline::core {

ExtensionModelOptions extensionOptionsFor(ModelSize size) {
    ExtensionModelOptions o;
    switch (size) {
    case ModelSize::Small:
        o.columns = 120;
        o.layers = 4;
        o.rows = 30;
        break;
    case ModelSize::Medium:
        break; // 250 x 4 x 60 = 60,000
    case ModelSize::Large:
        o.columns = 350;
        o.layers = 10;
        o.rows = 150;
        o.settleSteps = 2500; // a taller model takes longer to settle under gravity
        break;
    }
    return o;
}

ExtensionModelOptions extensionDemoOptions() {
    ExtensionModelOptions o;
    o.columns = 128; // 256 radii along the extension (x)
    o.layers = 40;   // 65 radii along strike (y)
    o.rows = 40;     // 69 radii tall
    o.frames = 40;
    o.discontinuities = {0.3, 0.7};
    // Oblique discontinuities: 38 radii further east at the north side than at the south, so
    // the grabens and their faults run oblique and change place along strike. (Segments make
    // the step a vertical transfer zone whose damage fills the view between the faults.)
    o.obliquity = 0.15;
    o.segments = 0;
    return o;
}

void validate(const ExtensionModelOptions& o) {
    auto need = [](bool ok, const std::string& what) {
        if (!ok)
            throw std::invalid_argument(what);
    };
    need(o.columns >= 4 && o.layers >= 1 && o.rows >= 4,
         "the lattice needs at least 4 columns, 1 layer and 4 rows");
    need(static_cast<double>(o.columns) * o.layers * o.rows < 4.0e9, "the lattice is too large");
    need(o.strainMean > 0 && o.strainSd >= 0, "the normal law needs mean > 0 and sd >= 0");
    need(o.weibullShape > 0 && o.weibullScale > 0, "the Weibull law needs shape and scale > 0");
    need(o.minBreakingStrain > 0, "the minimum breaking strain must be > 0");
    need(o.gravityRatio >= 0, "the gravity ratio must be >= 0");
    need(o.friction >= 0, "friction must be >= 0");
    need(o.localDamping >= 0 && o.localDamping < 1, "local damping must be in [0, 1)");
    need(o.dashpotRatio >= 0 && o.dashpotRatio <= 1, "the dashpot ratio must be in [0, 1]");
    need(o.dtFactor > 0 && o.dtFactor <= 0.5, "the time step factor must be in (0, 0.5]");
    need(o.extension > 0 && o.extension <= 1, "extension must be in (0, 1]");
    need(o.velocity > 0 && o.velocity <= 0.5, "velocity must be in (0, 0.5]");
    need(!o.discontinuities.empty() && o.discontinuities.size() <= 16,
         "give 1 to 16 base discontinuities");
    for (double d : o.discontinuities)
        need(d > 0 && d < 1, "discontinuities must be in (0, 1)");
    need(o.stretchWidth >= 0 && o.stretchWidth <= 1, "the stretch width must be in [0, 1]");
    need(o.obliquity >= -0.5 && o.obliquity <= 0.5, "the obliquity must be in [-0.5, 0.5]");
    need(o.segments >= 0 && o.segments <= 64, "segments must be in 0..64");
    need(o.settleSteps >= 0, "settle steps must be >= 0");
    need(o.frames >= 1 && o.frames <= 100000, "frames must be in 1..100000");
    need(o.layerBands >= 1, "layer bands must be >= 1");
    need(o.threads >= 0, "threads must be >= 0");
}

std::string describeExtensionRun(const ExtensionModelOptions& o, const ExtensionRunStats& s) {
    nlohmann::json j;
    j["model"] = "bonded DEM extension";
    j["lattice"] = {{"columns", o.columns}, {"layers", o.layers}, {"rows", o.rows}};
    j["seed"] = o.seed;
    j["breaking_strain"] =
        o.law == BreakingStrainLaw::Normal
            ? nlohmann::json{{"law", "normal"}, {"mean", o.strainMean}, {"sd", o.strainSd}}
            : nlohmann::json{
                  {"law", "weibull"}, {"shape", o.weibullShape}, {"scale", o.weibullScale}};
    j["min_breaking_strain"] = o.minBreakingStrain;
    j["gravity_ratio"] = o.gravityRatio;
    j["friction"] = o.friction;
    j["local_damping"] = o.localDamping;
    j["dashpot_ratio"] = o.dashpotRatio;
    j["dt_factor"] = o.dtFactor;
    j["extension"] = o.extension;
    j["velocity"] = o.velocity;
    j["discontinuities"] = o.discontinuities;
    j["stretch_width"] = o.stretchWidth;
    j["obliquity"] = o.obliquity;
    j["segments"] = o.segments;
    j["settle_steps"] = o.settleSteps;
    j["frames"] = s.frames;
    j["layer_bands"] = o.layerBands;
    j["spheres"] = s.spheres;
    j["bonds"] = s.bonds;
    j["broken_bonds"] = s.brokenBonds;
    j["steps"] = s.steps;
    j["stepping_seconds"] = s.simulationSeconds;
    j["total_seconds"] = s.totalSeconds;
    j["steps_per_second"] = s.stepsPerSecond();
    j["sphere_steps_per_second"] = s.sphereStepsPerSecond();
    return j.dump(2);
}

const std::vector<std::string>& extensionDumpColumns() {
    static const std::vector<std::string> columns = {
        "id", "type", "x", "y", "z", "radius", "strain", "broken_bonds", "layer", "x0", "y0", "z0"};
    return columns;
}

} // namespace faultline::core
