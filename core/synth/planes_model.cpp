// Index of this file:
// [SECTION] Geometry: vectors, discs, planes
// [SECTION] Offsetting points across faults
// [SECTION] Checking options
// [SECTION] Presets
// [SECTION] Generating the model
// [SECTION] The network preset, truth JSON and files

#include "core/synth/planes_model.hpp"

#include "core/synth/dump_writer.hpp"
#include "core/synth/hcp_lattice.hpp"
#include "core/synth/seeded_random.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

namespace faultline::core {

namespace {

using Vec = std::array<double, 3>;

constexpr double kDeg = std::numbers::pi / 180.0;

double dotv(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
//-----------------------------------------------------------------------------
// [SECTION] Geometry: vectors, discs, planes
//-----------------------------------------------------------------------------

Vec addScaled(const Vec& a, double s, const Vec& b) {
    return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}

// Down-dip unit vector: the direction a hanging wall slides in a normal fault.
Vec downDip(double dip, double dipDirection) {
    const double d = dip * kDeg, a = dipDirection * kDeg;
    return {std::cos(d) * std::sin(a), std::cos(d) * std::cos(a), -std::sin(d)};
}

double wrapDegrees(double deg) {
    double w = std::fmod(deg, 360.0);
    return w < 0 ? w + 360.0 : w;
}

// Distance from a point to a disc (centre c, unit normal n, radius r).
double pointDiscDistance(const Vec& p, const Vec& c, const Vec& n, double r) {
    const Vec d = sub(p, c);
    const double h = dotv(d, n);
    const Vec inPlane = addScaled(d, -h, n);
    const double rho = std::sqrt(dotv(inPlane, inPlane));
    return rho <= r ? std::fabs(h) : std::sqrt(h * h + (rho - r) * (rho - r));
}

// Two unit vectors spanning the plane with normal n.
std::pair<Vec, Vec> planeBasis(const Vec& n) {
    const Vec helper = std::fabs(n[2]) < 0.9 ? Vec{0, 0, 1} : Vec{1, 0, 0};
    Vec u = {n[1] * helper[2] - n[2] * helper[1], n[2] * helper[0] - n[0] * helper[2],
             n[0] * helper[1] - n[1] * helper[0]};
    const double len = std::sqrt(dotv(u, u));
    u = {u[0] / len, u[1] / len, u[2] / len};
    const Vec v = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    return {u, v};
}

// Smallest distance between two discs, from points sampled on each (spacing below 1 radius) to
// the other disc exactly; low by at most half the spacing.
double discGap(const PlaneFaultSpec& a, const Vec& na, const PlaneFaultSpec& b, const Vec& nb) {
    double best = 1e300;
    auto sampleAgainst = [&](const PlaneFaultSpec& s, const Vec& ns, const PlaneFaultSpec& o,
                             const Vec& no) {
        const auto [u, v] = planeBasis(ns);
        const int rings = std::max(2, static_cast<int>(std::ceil(s.radius)));
        for (int k = 0; k <= rings; ++k) {
            const double rho = s.radius * k / rings;
            const int around = std::max(1, static_cast<int>(std::ceil(2 * std::numbers::pi * rho)));
            for (int m = 0; m < around; ++m) {
                const double t = 2 * std::numbers::pi * m / around;
                const Vec p =
                    addScaled(addScaled(s.centre, rho * std::cos(t), u), rho * std::sin(t), v);
                best = std::min(best, pointDiscDistance(p, o.centre, no, o.radius));
            }
        }
    };
    sampleAgainst(a, na, b, nb);
    sampleAgainst(b, nb, a, na);
    return best;
}

//-----------------------------------------------------------------------------
// [SECTION] Offsetting points across faults
//-----------------------------------------------------------------------------

// Where a point lies relative to a fault's surface: signed distance h (positive on the side the
// upward normal points to, the hanging wall), distance rho from the centre within the surface,
// and the dip of the surface at the nearest point (degrees).
struct SurfaceCoords {
    double h = 0, rho = 0, dip = 0;
};

class FaultSurface {
  public:
    explicit FaultSurface(const PlaneFaultSpec& s) : m_spec(s) {
        m_normal = planeNormalOf(s.dip, s.dipDirection);
        if (!s.listricDip)
            return;
        // The listric trace in the vertical section along the dip direction: (u, z) from arc
        // length -L (top) to +L (bottom), the dip varying evenly with arc length.
        const double a = s.dipDirection * kDeg;
        m_alongDip = {std::sin(a), std::cos(a), 0};
        m_alongStrike = {-std::cos(a), std::sin(a), 0};
        const double length = s.radius * 1.25, step = 0.25;
        const int half = static_cast<int>(std::ceil(length / step));
        auto dipAt = [&](double arc) {
            const double f = std::clamp((arc + s.radius) / (2 * s.radius), 0.0, 1.0);
            return s.dip + (*s.listricDip - s.dip) * f;
        };
        std::vector<std::array<double, 3>> down{{0, 0, 0}}, up{{0, 0, 0}}; // u, z, arc
        for (int k = 1; k <= half; ++k) {
            const auto& pd = down.back();
            const double dd = dipAt(pd[2] + step / 2) * kDeg;
            down.push_back(
                {pd[0] + std::cos(dd) * step, pd[1] - std::sin(dd) * step, pd[2] + step});
            const auto& pu = up.back();
            const double du = dipAt(pu[2] - step / 2) * kDeg;
            up.push_back({pu[0] - std::cos(du) * step, pu[1] + std::sin(du) * step, pu[2] - step});
        }
        m_trace.assign(up.rbegin(), up.rend());
        m_trace.insert(m_trace.end(), down.begin() + 1, down.end());
        m_traceDip.resize(m_trace.size());
        for (std::size_t k = 0; k < m_trace.size(); ++k)
            m_traceDip[k] = dipAt(m_trace[k][2]);
    }

    SurfaceCoords at(const Vec& p) const {
        const Vec d = sub(p, m_spec.centre);
        SurfaceCoords c;
        if (!m_spec.listricDip) {
            c.h = dotv(d, m_normal);
            const Vec inPlane = addScaled(d, -c.h, m_normal);
            c.rho = std::sqrt(dotv(inPlane, inPlane));
            c.dip = m_spec.dip;
            return c;
        }
        const double u = dotv(d, m_alongDip), z = d[2], w = dotv(d, m_alongStrike);
        double best = 1e300;
        for (std::size_t k = 0; k + 1 < m_trace.size(); ++k) {
            const auto& p0 = m_trace[k];
            const auto& p1 = m_trace[k + 1];
            const double eu = p1[0] - p0[0], ez = p1[1] - p0[1];
            const double t =
                std::clamp(((u - p0[0]) * eu + (z - p0[1]) * ez) / (eu * eu + ez * ez), 0.0, 1.0);
            const double qu = u - (p0[0] + t * eu), qz = z - (p0[1] + t * ez);
            const double dist2 = qu * qu + qz * qz;
            if (dist2 < best) {
                best = dist2;
                const double dip = (m_traceDip[k] + t * (m_traceDip[k + 1] - m_traceDip[k])) * kDeg;
                c.h = qu * std::sin(dip) + qz * std::cos(dip); // along the upward normal
                c.dip = dip / kDeg;
                const double arc = p0[2] + t * (p1[2] - p0[2]);
                c.rho = std::sqrt(arc * arc + w * w);
            }
        }
        return c;
    }

    // The direction a hanging wall slides at a point whose surface dip is `dip`.
    Vec downDipAt(double dip) const { return downDip(dip, m_spec.dipDirection); }

  private:
    static Vec planeNormalOf(double dip, double dipDirection) {
        const double d = dip * kDeg, a = dipDirection * kDeg;
        return {std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d)};
    }
    PlaneFaultSpec m_spec;
    Vec m_normal{0, 0, 1};
    Vec m_alongDip{1, 0, 0}, m_alongStrike{0, 1, 0};
    std::vector<std::array<double, 3>> m_trace; // u, z, arc length
    std::vector<double> m_traceDip;
};

//-----------------------------------------------------------------------------
// [SECTION] Checking options
//-----------------------------------------------------------------------------

void check(const PlanesModelOptions& o) {
    auto need = [](bool ok, const std::string& what) {
        if (!ok)
            throw std::invalid_argument(what);
    };
    need(o.columns >= 2 && o.layers >= 2 && o.rows >= 2,
         "the block needs at least 2 spheres a side");
    need(static_cast<double>(o.columns) * o.layers * o.rows < 2.0e8, "the block is too large");
    need(o.frames >= 1 && o.frames <= 10000, "frames must be in 1..10000");
    need(o.faults.empty() ? o.faultCount >= 0 && o.faultCount <= 100 : true,
         "the fault count must be in 0..100");
    need(!o.dip || (*o.dip > 0 && *o.dip <= 90), "dip must be in (0, 90]");
    need(!o.throwLength || *o.throwLength >= 0, "throw must be >= 0");
    need(o.halfThickness > 0, "the half thickness must be > 0");
    need(o.layerBands >= 1, "layer bands must be >= 1");
    for (const auto& f : o.faults) {
        need(f.dip > 0 && f.dip <= 90, "a fault's dip must be in (0, 90]");
        need(f.radius > 0 && f.throwLength >= 0, "a fault needs radius > 0 and throw >= 0");
        need(f.appearsAt >= 0 && f.appearsAt < 1, "a fault's start must be in [0, 1)");
        need(f.endsAgainst < static_cast<int>(o.faults.size()),
             "a fault ends against a fault that is not there");
        need(!f.listricDip || (*f.listricDip > 0 && *f.listricDip <= 90),
             "a listric dip must be in (0, 90]");
    }
    need(o.noiseFraction >= 0 && o.noiseFraction < 0.5, "the noise fraction must be in [0, 0.5)");
}

} // namespace

std::array<double, 3> planeNormal(double dip, double dipDirection) {
    const double d = dip * kDeg, a = dipDirection * kDeg;
    return {std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d)};
}

//-----------------------------------------------------------------------------
// [SECTION] Presets
//-----------------------------------------------------------------------------

PlanesModelOptions planesOptionsFor(ModelSize size) {
    PlanesModelOptions o;
    switch (size) {
    case ModelSize::Small:
        o.columns = 24;
        o.layers = 18;
        o.rows = 16;
        o.faultCount = 2;
        break;
    case ModelSize::Medium:
        break;
    case ModelSize::Large:
        o.columns = 80;
        o.layers = 60;
        o.rows = 56;
        o.faultCount = 6;
        break;
    }
    return o;
}

//-----------------------------------------------------------------------------
// [SECTION] Generating the model
//-----------------------------------------------------------------------------

PlanesModel generatePlanesModel(const PlanesModelOptions& options) {
    check(options);
    PlanesModel model;
    model.options = options;
    const HcpLattice lat = makeHcpLattice(options.columns, options.layers, options.rows);
    const std::size_t n = lat.size();
    const Vec hi = lat.hi;
    SeededRandom rng(options.seed);

    // Faults: as given, or random ones placed apart by rejection.
    std::vector<PlaneFaultSpec> specs = options.faults;
    if (specs.empty()) {
        const double smallest = std::min({hi[0], hi[1], hi[2]});
        for (int k = 0; k < options.faultCount; ++k) {
            bool placed = false;
            for (int attempt = 0; attempt < 2000 && !placed; ++attempt) {
                PlaneFaultSpec s;
                s.dip = options.dip ? *options.dip : rng.uniform(45, 75);
                s.dipDirection = options.dipDirection ? *options.dipDirection : rng.uniform(0, 360);
                s.throwLength = options.throwLength ? *options.throwLength : rng.uniform(4, 8);
                s.radius = rng.uniform(0.25, 0.4) * smallest;
                for (int a = 0; a < 3; ++a)
                    s.centre[a] = rng.uniform(0.25, 0.75) * hi[a];
                s.appearsAt = k == 0 ? 0.0 : rng.uniform(0.0, 0.5);
                const Vec ns = planeNormal(s.dip, s.dipDirection);
                placed = true;
                for (const auto& other : specs)
                    if (discGap(s, ns, other, planeNormal(other.dip, other.dipDirection)) <
                        2 * options.halfThickness + options.minGap) {
                        placed = false;
                        break;
                    }
                if (placed)
                    specs.push_back(s);
            }
            if (!placed)
                throw std::runtime_error(
                    "cannot place " + std::to_string(options.faultCount) +
                    " faults apart in this block: use fewer faults or a larger block");
        }
    }
    for (std::size_t k = 0; k < specs.size(); ++k) {
        PlaneFault f;
        f.name = "F" + std::to_string(k + 1);
        f.spec = specs[k];
        f.spec.dipDirection = wrapDegrees(f.spec.dipDirection);
        f.normal = planeNormal(f.spec.dip, f.spec.dipDirection);
        f.strike = wrapDegrees(f.spec.dipDirection - 90.0);
        f.slip = f.spec.throwLength / std::sin(f.spec.dip * kDeg);
        f.firstFrame = -1;
        model.faults.push_back(std::move(f));
    }

    // Per sphere, drawn once: background strain and the look of a damaged sphere.
    std::vector<float> backgroundStrain(n), zoneStrain(n);
    std::vector<std::int32_t> zoneBroken(n), band(n);
    for (std::size_t i = 0; i < n; ++i) {
        backgroundStrain[i] = static_cast<float>(rng.uniform(0.0, 0.02));
        zoneStrain[i] = static_cast<float>(rng.uniform(0.3, 0.6));
        zoneBroken[i] = 3 + static_cast<std::int32_t>(rng.uniform() * 6.0);
        band[i] =
            std::min(lat.rowOf[i] * options.layerBands / options.rows, options.layerBands - 1);
    }

    // Each sphere's place relative to each fault's surface, from its initial position, and
    // whether the fault may hold it (ends-against side, clip box).
    struct Placed {
        std::vector<SurfaceCoords> at;
        std::vector<std::uint8_t> allowed;
    };
    std::vector<FaultSurface> surfaces;
    for (const auto& f : model.faults)
        surfaces.emplace_back(f.spec);
    std::vector<Placed> placed(model.faults.size());
    for (std::size_t k = 0; k < model.faults.size(); ++k) {
        placed[k].at.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            placed[k].at[i] = surfaces[k].at(lat.positions[i]);
    }
    for (std::size_t k = 0; k < model.faults.size(); ++k) {
        const PlaneFaultSpec& s = model.faults[k].spec;
        placed[k].allowed.assign(n, 1);
        const double side =
            s.endsAgainst >= 0 ? surfaces[std::size_t(s.endsAgainst)].at(s.centre).h : 0;
        for (std::size_t i = 0; i < n; ++i) {
            const Vec& p = lat.positions[i];
            for (int a = 0; a < 3; ++a)
                if (p[a] < s.clipLo[a] || p[a] > s.clipHi[a])
                    placed[k].allowed[i] = 0;
            if (s.endsAgainst >= 0 && placed[std::size_t(s.endsAgainst)].at[i].h * side < 0)
                placed[k].allowed[i] = 0;
        }
    }
    // Noise: scattered spheres in no fault's final zone.
    std::vector<std::uint8_t> isNoise(n, 0);
    if (options.noiseFraction > 0) {
        for (std::size_t i = 0; i < n; ++i) {
            const bool draw = rng.uniform() < options.noiseFraction;
            bool member = false;
            for (std::size_t k = 0; k < model.faults.size() && !member; ++k)
                member = placed[k].allowed[i] &&
                         placed[k].at[i].rho <= model.faults[k].spec.radius &&
                         std::fabs(placed[k].at[i].h) <= options.halfThickness;
            if (draw && !member) {
                isNoise[i] = 1;
                model.noise.push_back(static_cast<std::int64_t>(i) + 1);
            }
        }
    }

    const double fadeDistance = options.halfThickness + 0.5 * options.minGap;
    const int frames = options.frames;
    for (int fr = 0; fr < frames; ++fr) {
        const double t = frames > 1 ? static_cast<double>(fr) / (frames - 1) : 1.0;
        std::vector<Vec> pos = lat.positions;
        std::vector<float> strain = backgroundStrain;
        std::vector<std::int32_t> broken(n, 0);
        for (std::size_t i = 0; i < n; ++i)
            if (isNoise[i]) {
                strain[i] = zoneStrain[i];
                broken[i] = zoneBroken[i];
            }
        for (std::size_t k = 0; k < model.faults.size(); ++k) {
            PlaneFault& f = model.faults[k];
            const PlaneFaultSpec& s = f.spec;
            const double grown = std::clamp((t - s.appearsAt) / (1.0 - s.appearsAt), 0.0, 1.0);
            const double radius = grown * s.radius, slip = grown * f.slip;
            std::vector<std::int64_t> members;
            if (radius > 0) {
                for (std::size_t i = 0; i < n; ++i) {
                    const SurfaceCoords& c = placed[k].at[i];
                    if (c.rho > radius || !placed[k].allowed[i])
                        continue;
                    const double taper = 1.0 - (c.rho / radius) * (c.rho / radius);
                    const double h = c.h;
                    if (std::fabs(h) <= options.halfThickness) {
                        members.push_back(static_cast<std::int64_t>(i) + 1);
                        strain[i] = std::max(strain[i],
                                             zoneStrain[i] * static_cast<float>(0.5 + 0.5 * grown));
                        broken[i] = std::max(broken[i], zoneBroken[i]);
                    }
                    // The hanging wall slides down-dip (parallel to the plane, so no sphere
                    // nears another zone), fading out before the gap to any other zone.
                    if (h > 0 && h < fadeDistance) {
                        const double fade = 1.0 - h / fadeDistance;
                        pos[i] =
                            addScaled(pos[i], slip * taper * fade, surfaces[k].downDipAt(c.dip));
                    }
                }
            }
            if (!members.empty() && f.firstFrame < 0)
                f.firstFrame = fr;
            f.members.push_back(std::move(members));
        }

        Frame frame;
        frame.timestep = fr;
        frame.ids.resize(n);
        frame.x.resize(n);
        frame.y.resize(n);
        frame.z.resize(n);
        frame.radius.assign(n, static_cast<float>(lat.radius));
        std::vector<std::int32_t> type(n, 1);
        std::vector<float> x0(n), y0(n), z0(n);
        auto q = [](double v) { return static_cast<float>(std::round(v * 1000.0) / 1000.0); };
        for (std::size_t i = 0; i < n; ++i) {
            frame.ids[i] = static_cast<std::int64_t>(i) + 1;
            frame.x[i] = q(pos[i][0]);
            frame.y[i] = q(pos[i][1]);
            frame.z[i] = q(pos[i][2]);
            x0[i] = q(lat.positions[i][0]);
            y0[i] = q(lat.positions[i][1]);
            z0[i] = q(lat.positions[i][2]);
            strain[i] = static_cast<float>(std::round(strain[i] * 1e4) / 1e4);
        }
        auto column = [](std::string name, auto&& values) {
            AttributeColumn c;
            c.name = std::move(name);
            if constexpr (std::is_same_v<std::decay_t<decltype(values)>, std::vector<float>>) {
                c.type = ColumnType::Float32;
                c.floats = std::move(values);
            } else {
                c.type = ColumnType::Int32;
                c.ints = std::move(values);
            }
            return c;
        };
        frame.attributes.push_back(column("type", std::move(type)));
        frame.attributes.push_back(column("strain", std::move(strain)));
        frame.attributes.push_back(column("broken_bonds", std::move(broken)));
        frame.attributes.push_back(column("layer", std::vector<std::int32_t>(band)));
        frame.attributes.push_back(column("x0", std::move(x0)));
        frame.attributes.push_back(column("y0", std::move(y0)));
        frame.attributes.push_back(column("z0", std::move(z0)));
        frame.box.known = true;
        frame.box.lo = {0, 0, 0};
        frame.box.hi = {std::round(hi[0] * 1000) / 1000, std::round(hi[1] * 1000) / 1000,
                        std::round(hi[2] * 1000) / 1000};
        frame.finalize();
        model.frames.push_back(std::move(frame));
    }
    std::vector<std::int64_t> all;
    for (const auto& f : model.faults)
        if (!f.members.empty())
            all.insert(all.end(), f.members.back().begin(), f.members.back().end());
    std::sort(all.begin(), all.end());
    for (std::size_t i = 1; i < all.size(); ++i)
        if (all[i] == all[i - 1] && (model.shared.empty() || model.shared.back() != all[i]))
            model.shared.push_back(all[i]);
    return model;
}

//-----------------------------------------------------------------------------
// [SECTION] The network preset, truth JSON and files
//-----------------------------------------------------------------------------

PlanesModelOptions planesNetworkOptions() {
    PlanesModelOptions o;
    o.columns = 64;
    o.layers = 60;
    o.rows = 40;
    o.frames = 4;
    o.noiseFraction = 0.003;
    const double hi = 1e300;
    auto fault = [&](double dip, double dipDirection, std::array<double, 3> centre, double yLo,
                     double yHi) {
        PlaneFaultSpec f;
        f.dip = dip;
        f.dipDirection = dipDirection;
        f.centre = centre;
        f.radius = 80;
        f.throwLength = 2;
        f.clipLo = {-hi, yLo, -hi};
        f.clipHi = {hi, yHi, hi};
        return f;
    };
    o.faults.push_back(fault(60, 90, {34, 28, 36}, -hi, 56));  // F1: X with F2
    o.faults.push_back(fault(60, 270, {34, 28, 36}, -hi, 56)); // F2
    o.faults.push_back(fault(60, 90, {84, 28, 40}, -hi, 56));  // F3: F4 ends against it
    o.faults.push_back(fault(65, 270, {104, 28, 52}, -hi, 56));
    o.faults.back().endsAgainst = 2;                         // F4: a V with F3 at depth
    o.faults.push_back(fault(70, 90, {50, 80, 36}, 62, hi)); // F5: listric, 70 to 30
    o.faults.back().listricDip = 30;
    o.faults.back().radius = 45;
    return o;
}

std::string planesTruthJson(const PlanesModel& model) {
    nlohmann::json j;
    j["kind"] = "planes";
    j["seed"] = model.options.seed;
    j["orientation"] = "+x east, +y north, +z up; dip in degrees below horizontal; dip_direction "
                       "the azimuth of steepest descent, degrees clockwise from north";
    j["spheres"] = model.frames.empty() ? 0 : model.frames.front().size();
    j["frames"] = model.frames.size();
    j["radius"] = 1.0;
    j["half_thickness"] = model.options.halfThickness;
    if (!model.frames.empty())
        j["box"] = {{"lo", model.frames.front().box.lo}, {"hi", model.frames.front().box.hi}};
    nlohmann::json faults = nlohmann::json::array();
    for (const auto& f : model.faults) {
        nlohmann::json jf;
        jf["name"] = f.name;
        jf["point"] = f.spec.centre;
        jf["normal"] = f.normal;
        jf["dip"] = f.spec.dip;
        jf["dip_direction"] = f.spec.dipDirection;
        jf["strike"] = f.strike;
        jf["throw"] = f.spec.throwLength;
        jf["slip"] = f.slip;
        jf["radius"] = f.spec.radius;
        jf["first_frame"] = f.firstFrame;
        if (f.spec.endsAgainst >= 0)
            jf["ends_against"] = model.faults[std::size_t(f.spec.endsAgainst)].name;
        if (f.spec.listricDip)
            jf["listric_dip"] = *f.spec.listricDip;
        jf["members"] = f.members;
        faults.push_back(std::move(jf));
    }
    j["faults"] = std::move(faults);
    j["shared"] = model.shared;
    j["noise"] = model.noise;
    return j.dump(1);
}

PlanesModelFiles writePlanesModel(const PlanesModel& model, const std::string& folder, bool gzip) {
    namespace fs = std::filesystem;
    fs::create_directories(folder);
    PlanesModelFiles files;
    files.dump = (fs::path(folder) / (gzip ? "planes.lammpstrj.gz" : "planes.lammpstrj")).string();
    files.truth = (fs::path(folder) / "planes_truth.json").string();
    LammpsDumpWriter writer(files.dump, gzip ? 6 : 0);
    for (const auto& f : model.frames)
        writer.write(f, extensionDumpColumns());
    writer.close();
    std::ofstream out(files.truth, std::ios::binary);
    out << planesTruthJson(model) << '\n';
    out.close();
    if (!out)
        throw std::runtime_error(files.truth + ": write failed");
    return files;
}

} // namespace faultline::core
