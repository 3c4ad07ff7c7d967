// `faultline generate`: the built-in models. The bonded-sphere extension demo, and planar faults
// with a known answer (ground truth JSON) for tests.
#include "app/cli.hpp"

#include "core/synth/demo_model.hpp"
#include "core/synth/dump_writer.hpp"
#include "core/synth/extension_model.hpp"
#include "core/synth/planes_model.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace faultline::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: faultline generate --demo\n"
    "       faultline generate --kind block [options] --out DIR\n"
    "       faultline generate [--kind extension|section] [--size small|medium|large] [options] "
    "--out DIR\n"
    "       faultline generate --kind planes [--faults N | --network] [options] --out DIR\n"
    "\n"
    "  --demo              build the demo model (the 3-D block) once into the per-user data\n"
    "                      folder and print its path (later runs reuse it)\n"
    "  --kind K            block (the 3-D demo block: 204,800 spheres, 40 frames, oblique\n"
    "                      discontinuities), extension (bonded DEM sandbox, default),\n"
    "                      section (the same, a thin 2-D section: fast, for tests) or planes\n"
    "                      (known faults)\n"
    "  --size S            small, medium (default) or large: 14k, 60k or 525k spheres\n"
    "                      (extension), 7k, 34k or 269k (planes)\n"
    "  --seed S            random seed (default 1)\n"
    "  --frames F          frames to write\n"
    "  --gzip              write the dump gzip-compressed\n"
    "  --threads T         worker threads (default: all cores); results depend on seed only\n"
    "extension options:\n"
    "  --law normal|weibull        breaking strain law (default normal)\n"
    "  --strain-mean M --strain-sd S         normal law (default 0.01, 0.002)\n"
    "  --weibull-shape K --weibull-scale L   Weibull law (default 6, 0.0108)\n"
    "  --gravity-ratio G   column weight over mean bond strength (default 5)\n"
    "  --friction MU       contact friction (default 0.5)\n"
    "  --extension E       final extension, fraction of the length (default 0.05)\n"
    "  --velocity V        speed of the moving side, radii per time unit (default 0.02)\n"
    "  --discontinuities A,B,...   where the base steps, fractions of the length (default "
    "0.3,0.7)\n"
    "  --stretch-width W   stretch the base uniformly over this fraction instead (default 0)\n"
    "  --obliquity O       along strike (y) the discontinuities shift by O x length from one\n"
    "                      side to the other (default 0; block 0.15)\n"
    "  --segments N        ... in N straight en echelon steps instead of a line (default 0)\n"
    "  --columns NX --layers NY --rows NZ    lattice size (overrides --size)\n"
    "planes options:\n"
    "  --network           a fault network instead of random faults: an X crossing, a fault\n"
    "                      ending against another at depth (V), a listric fault (70 to 30\n"
    "                      degrees), 0.3% noise spheres; ~154k spheres. The truth JSON lists\n"
    "                      the ids two zones share (\"shared\") and the noise ids\n"
    "  --faults N          number of faults (default 3)\n"
    "  --dip D             dip of every fault in degrees (default: random 45-75)\n"
    "  --dip-direction A   dip direction of every fault, degrees clockwise from north\n"
    "                      (default: random)\n"
    "  --throw T           final throw in radii (default: random 4-8)\n";

struct Parsed {
    std::optional<std::string> value(const std::string& name) const {
        for (std::size_t i = 0; i + 1 < args.size(); ++i)
            if (args[i] == name)
                return args[i + 1];
        return std::nullopt;
    }
    bool flag(const std::string& name) const {
        for (const auto& a : args)
            if (a == name)
                return true;
        return false;
    }
    Args args;
};

double toDouble(const std::string& name, const std::string& text) {
    double v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size())
        throw std::invalid_argument(name + " expects a number, got '" + text + "'");
    return v;
}

long long toInteger(const std::string& name, const std::string& text) {
    long long v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size())
        throw std::invalid_argument(name + " expects an integer, got '" + text + "'");
    return v;
}

void checkKnown(const Args& args) {
    static const std::vector<std::string> valued = {
        "--kind",          "--size",          "--seed",          "--frames",
        "--threads",       "--out",           "--law",           "--strain-mean",
        "--strain-sd",     "--weibull-shape", "--weibull-scale", "--gravity-ratio",
        "--friction",      "--extension",     "--velocity",      "--discontinuities",
        "--stretch-width", "--columns",       "--layers",        "--rows",
        "--faults",        "--dip",           "--dip-direction", "--throw",
        "--obliquity",     "--segments"};
    static const std::vector<std::string> flags = {"--demo", "--gzip", "--network"};
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (std::find(valued.begin(), valued.end(), args[i]) != valued.end()) {
            if (i + 1 >= args.size())
                throw std::invalid_argument(args[i] + " needs a value");
            ++i;
        } else if (std::find(flags.begin(), flags.end(), args[i]) == flags.end()) {
            throw std::invalid_argument("unknown argument '" + args[i] + "'");
        }
    }
}

class StderrProgress {
  public:
    explicit StderrProgress(std::string label) : m_label(std::move(label)) {}
    bool operator()(double fraction) {
        const int pct = static_cast<int>(fraction * 100.0 + 0.5);
        if (pct != m_last) {
            m_last = pct;
            std::fprintf(stderr, "\r%s: %3d%%", m_label.c_str(), pct);
            if (pct >= 100)
                std::fprintf(stderr, "\n");
            std::fflush(stderr);
        }
        return true;
    }

  private:
    std::string m_label;
    int m_last = -1;
};

core::ModelSize parseSize(const std::string& s) {
    if (s == "small")
        return core::ModelSize::Small;
    if (s == "medium")
        return core::ModelSize::Medium;
    if (s == "large")
        return core::ModelSize::Large;
    throw std::invalid_argument("--size expects small, medium or large, got '" + s + "'");
}

int runExtension(const Parsed& a, const fs::path& out, bool block) {
    if (block && a.value("--size"))
        throw std::invalid_argument(
            "--kind block has one size; set --columns --layers --rows instead");
    core::ExtensionModelOptions o =
        block ? core::extensionDemoOptions()
              : core::extensionOptionsFor(parseSize(a.value("--size").value_or("medium")));
    if (auto v = a.value("--seed"))
        o.seed = static_cast<std::uint64_t>(toInteger("--seed", *v));
    if (auto v = a.value("--frames"))
        o.frames = static_cast<int>(toInteger("--frames", *v));
    if (auto v = a.value("--threads"))
        o.threads = static_cast<int>(toInteger("--threads", *v));
    if (auto v = a.value("--law")) {
        if (*v == "normal")
            o.law = core::BreakingStrainLaw::Normal;
        else if (*v == "weibull")
            o.law = core::BreakingStrainLaw::Weibull;
        else
            throw std::invalid_argument("--law expects normal or weibull, got '" + *v + "'");
    }
    struct {
        const char* name;
        double* target;
    } reals[] = {{"--strain-mean", &o.strainMean},     {"--strain-sd", &o.strainSd},
                 {"--weibull-shape", &o.weibullShape}, {"--weibull-scale", &o.weibullScale},
                 {"--gravity-ratio", &o.gravityRatio}, {"--friction", &o.friction},
                 {"--extension", &o.extension},        {"--velocity", &o.velocity},
                 {"--stretch-width", &o.stretchWidth}, {"--obliquity", &o.obliquity}};
    for (auto& r : reals)
        if (auto v = a.value(r.name))
            *r.target = toDouble(r.name, *v);
    if (auto v = a.value("--discontinuities")) {
        o.discontinuities.clear();
        std::size_t start = 0;
        while (start <= v->size()) {
            const std::size_t comma = std::min(v->find(',', start), v->size());
            o.discontinuities.push_back(
                toDouble("--discontinuities", v->substr(start, comma - start)));
            start = comma + 1;
        }
    }
    if (auto v = a.value("--segments"))
        o.segments = static_cast<int>(toInteger("--segments", *v));
    if (auto v = a.value("--columns"))
        o.columns = static_cast<int>(toInteger("--columns", *v));
    if (auto v = a.value("--layers"))
        o.layers = static_cast<int>(toInteger("--layers", *v));
    if (auto v = a.value("--rows"))
        o.rows = static_cast<int>(toInteger("--rows", *v));
    core::validate(o);

    fs::create_directories(out);
    const bool gz = a.flag("--gzip");
    const fs::path dump = out / (gz ? "extension.lammpstrj.gz" : "extension.lammpstrj");
    core::LammpsDumpWriter writer(dump.string(), gz ? 1 : 0);
    StderrProgress progress("extension model");
    const auto stats = core::runExtensionModel(
        o, [&](const core::Frame& f, int) { writer.write(f, core::extensionDumpColumns()); },
        std::ref(progress));
    writer.close();
    const fs::path info = out / "extension.json";
    std::ofstream(info) << core::describeExtensionRun(o, stats) << "\n";
    std::printf("%s\n", dump.string().c_str());
    std::fprintf(stderr,
                 "%zu spheres, %zu bonds (%zu broken), %lld steps, %d frames\n"
                 "stepping %.1f s: %.0f steps/s, %.3g sphere-steps/s; total %.1f s\n",
                 stats.spheres, stats.bonds, stats.brokenBonds, static_cast<long long>(stats.steps),
                 stats.frames, stats.simulationSeconds, stats.stepsPerSecond(),
                 stats.sphereStepsPerSecond(), stats.totalSeconds);
    return 0;
}

int runPlanes(const Parsed& a, const fs::path& out) {
    core::PlanesModelOptions o;
    if (a.flag("--network")) {
        if (a.value("--size") || a.value("--faults") || a.value("--dip") ||
            a.value("--dip-direction") || a.value("--throw"))
            throw std::invalid_argument("--network sets the faults and the size; drop --size, "
                                        "--faults, --dip, --dip-direction and --throw");
        o = core::planesNetworkOptions();
    }
    if (auto v = a.value("--size")) {
        const auto size = parseSize(*v);
        o = core::planesOptionsFor(size);
    }
    if (auto v = a.value("--seed"))
        o.seed = static_cast<std::uint64_t>(toInteger("--seed", *v));
    if (auto v = a.value("--frames"))
        o.frames = static_cast<int>(toInteger("--frames", *v));
    if (auto v = a.value("--faults"))
        o.faultCount = static_cast<int>(toInteger("--faults", *v));
    if (auto v = a.value("--dip"))
        o.dip = toDouble("--dip", *v);
    if (auto v = a.value("--dip-direction"))
        o.dipDirection = toDouble("--dip-direction", *v);
    if (auto v = a.value("--throw"))
        o.throwLength = toDouble("--throw", *v);
    if (auto v = a.value("--columns"))
        o.columns = static_cast<int>(toInteger("--columns", *v));
    if (auto v = a.value("--layers"))
        o.layers = static_cast<int>(toInteger("--layers", *v));
    if (auto v = a.value("--rows"))
        o.rows = static_cast<int>(toInteger("--rows", *v));
    const core::PlanesModel model = core::generatePlanesModel(o);
    const auto files = core::writePlanesModel(model, out.string(), a.flag("--gzip"));
    std::printf("%s\n%s\n", files.dump.c_str(), files.truth.c_str());
    std::fprintf(stderr, "%zu spheres, %zu faults, %zu frames\n", model.frames.front().size(),
                 model.faults.size(), model.frames.size());
    return 0;
}

} // namespace

int runGenerate(const Args& args) {
    Parsed a{args};
    if (a.flag("--help") || a.flag("-h")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    try {
        checkKnown(args);
        if (a.flag("--demo")) {
            StderrProgress progress("building the demo model (once)");
            const std::string path = core::ensureDemoModel(std::ref(progress));
            std::printf("%s\n", path.c_str());
            return 0;
        }
        const auto out = a.value("--out");
        if (!out) {
            std::fprintf(stderr, "faultline generate: --out DIR is required\n%s", kUsage);
            return 2;
        }
        const std::string kind = a.value("--kind").value_or("extension");
        if (kind == "extension" || kind == "section")
            return runExtension(a, *out, false);
        if (kind == "block")
            return runExtension(a, *out, true);
        if (kind == "planes")
            return runPlanes(a, *out);
        throw std::invalid_argument("--kind expects block, section, extension or planes, got '" +
                                    kind + "'");
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "faultline generate: %s\n%s", e.what(), kUsage);
        return 2;
    }
}

} // namespace faultline::app
