// Index of this file:
// [SECTION] Vectors and constants
// [SECTION] The model's state
// [SECTION] Building and settling the block
// [SECTION] Contacts and bonds
// [SECTION] Forces and integration
// [SECTION] Advancing and snapshots

#include "core/synth/extension_model.hpp"

#include "core/synth/hcp_lattice.hpp"
#include "core/synth/local_strain.hpp"
#include "core/synth/seeded_random.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>

namespace faultline::core {

namespace {

//-----------------------------------------------------------------------------
// [SECTION] Vectors and constants
//-----------------------------------------------------------------------------

struct V3 {
    double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3& operator+=(V3& a, V3 b) { return a = a + b; }
inline V3& operator-=(V3& a, V3 b) { return a = a - b; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

constexpr double kRadius = 1.0;
constexpr double kMass = 1.0;
constexpr double kStiffness = 1.0;
constexpr double kSkin = 0.4;   // Verlet list margin, radii
constexpr int kRampSteps = 400; // the moving side accelerates smoothly over these steps
constexpr std::size_t kGrain = 1024;
// Where segmented discontinuities step, the step is a ramp this share of a segment wide.
constexpr double kRelayShare = 0.5;

double quantize(double v, double step) { return std::round(v / step) * step; }

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] The model's state
//-----------------------------------------------------------------------------

// Basal spheres move kinematically; side spheres (the first and last of every row) are welded
// in x to the end plates but free in y and z, so the model settles and slides along them.
enum class SphereKind : std::uint8_t { Free, Basal, Side };

struct ExtensionModel::State {
    ExtensionModelOptions opt;
    mutable tbb::task_arena arena; // executing work does not change the model
    double dt = 0, g = 0, bondDashpot = 0, length = 0;
    std::int64_t step = 0, frameInterval = 1;

    std::size_t n = 0;
    std::vector<V3> x0, p, v, pBuild; // x0: lattice positions
    // Settled positions (the lattice until settling ends): the reference of strain and x0 y0 z0.
    std::vector<std::array<double, 3>> reference;
    std::vector<SphereKind> kind;
    std::vector<double> baseWeight; // fraction of the moving side's displacement (below it)
    std::vector<std::int32_t> band;
    std::array<double, 3> boxHi{};

    // Bonds (i < j): breaking strain, broken flag, force on the first sphere this step.
    std::vector<std::array<std::uint32_t, 2>> bonds;
    std::vector<double> breakStrain;
    std::vector<double> installedLength; // bonds are installed (cemented) once settled
    std::vector<std::uint8_t> broken;
    std::vector<V3> bondForce;
    // Each sphere's bonds: entry = 2 * bond + (sphere is the bond's second end).
    std::vector<std::uint32_t> bondOffsets, bondEntries;
    NeighbourTable strainNeighbours; // every lattice neighbour, for the strain measure

    // Verlet list of candidate contacts: partner and its bond (-1 when none).
    std::vector<std::uint32_t> contactOffsets, contactPartner;
    std::vector<std::int32_t> contactBond;

    // Displacement and speed of the moving side after `s` steps.
    double displacementAt(std::int64_t s) const {
        const double t = static_cast<double>(s - opt.settleSteps) * dt;
        if (t <= 0)
            return 0;
        const double ramp = kRampSteps * dt;
        const double u =
            t < ramp ? opt.velocity * t * t / (2 * ramp) : opt.velocity * (t - ramp / 2);
        return std::min(u, opt.extension * length);
    }
    double speedAt(std::int64_t s) const {
        const double t = static_cast<double>(s - opt.settleSteps) * dt;
        if (t <= 0 || displacementAt(s) >= opt.extension * length)
            return 0;
        return opt.velocity * std::min(1.0, t / (kRampSteps * dt));
    }

    void buildContacts();
    void installBonds();
    void computeBondForces();
    void computeSphereForces(std::vector<V3>& acc);
    double integrate(const std::vector<V3>& acc);
};

//-----------------------------------------------------------------------------
// [SECTION] Building and settling the block
//-----------------------------------------------------------------------------

ExtensionModel::ExtensionModel(const ExtensionModelOptions& options)
    : m(std::make_unique<State>()) {
    State& s = *m;
    s.opt = options;
    const auto& o = s.opt;
    assert(o.columns > 2 && o.layers > 0 && o.rows > 2 && o.frames >= 1);
    s.arena.initialize(o.threads > 0 ? o.threads : tbb::task_arena::automatic);

    const HcpLattice lat = makeHcpLattice(o.columns, o.layers, o.rows, kRadius);
    s.n = lat.size();
    s.boxHi = lat.hi;
    s.length = lat.hi[0];
    s.x0.resize(s.n);
    for (std::size_t i = 0; i < s.n; ++i)
        s.x0[i] = {lat.positions[i][0], lat.positions[i][1], lat.positions[i][2]};
    s.p = s.x0;
    s.pBuild = s.x0;
    s.v.assign(s.n, V3{});

    // Basal spheres: the first row of every plane; side spheres: the ends of every other row.
    // Their share of the moving side's displacement is a step at the discontinuity, or a linear
    // ramp across the stretching zone. Free spheres get the share of the base beneath them: the
    // frame their damping works in.
    s.kind.assign(s.n, SphereKind::Free);
    s.baseWeight.assign(s.n, 0.0);
    const double half = 0.5 * o.stretchWidth * s.length;
    // Where the discontinuities lie at a given y (along strike), as a shift of x.
    auto shiftAt = [&](double y) {
        double t = std::clamp(s.boxHi[1] > 0 ? y / s.boxHi[1] : 0.5, 0.0, 1.0);
        if (o.segments >= 2) {
            // Steps between segments, each a ramp kRelayShare of a segment wide: the base
            // bends there instead of shearing along a vertical plane.
            const double u = t * o.segments - 0.5; // segment centres at whole numbers
            const double k = std::floor(u), f = u - k;
            const double ramp = std::clamp((f - 0.5) / kRelayShare + 0.5, 0.0, 1.0);
            t = std::clamp(k + ramp, 0.0, double(o.segments - 1)) / (o.segments - 1);
        }
        return o.obliquity * s.length * (t - 0.5);
    };
    auto weightAt = [&](double x, double y) {
        double w = 0;
        for (double d : o.discontinuities) {
            const double xd = d * s.length + shiftAt(y);
            w += half > 0 ? std::clamp((x - (xd - half)) / (2 * half), 0.0, 1.0)
                          : (x > xd ? 1.0 : 0.0);
        }
        return w / static_cast<double>(o.discontinuities.size());
    };
    for (std::size_t i = 0; i < s.n; ++i) {
        const int column = static_cast<int>(i % static_cast<std::size_t>(o.columns));
        if (lat.rowOf[i] == 0)
            s.kind[i] = SphereKind::Basal;
        else if (column == 0 || column == o.columns - 1)
            s.kind[i] = SphereKind::Side;
        // The end plates move with the ends of the base.
        s.baseWeight[i] = s.kind[i] == SphereKind::Side ? (column == 0 ? 0.0 : 1.0)
                                                        : weightAt(s.x0[i].x, s.x0[i].y);
    }
    s.reference = lat.positions;
    s.band.resize(s.n);
    for (std::size_t i = 0; i < s.n; ++i)
        s.band[i] = std::min(lat.rowOf[i] * o.layerBands / o.rows, o.layerBands - 1);

    // Bonds: every touching pair except two basal spheres (both moved by the base).
    SeededRandom rng(o.seed);
    for (const auto& pr : lat.pairs) {
        if (s.kind[pr[0]] == SphereKind::Basal && s.kind[pr[1]] == SphereKind::Basal)
            continue;
        double e = o.law == BreakingStrainLaw::Normal ? rng.normal(o.strainMean, o.strainSd)
                                                      : rng.weibull(o.weibullShape, o.weibullScale);
        s.bonds.push_back(pr);
        s.breakStrain.push_back(std::max(e, o.minBreakingStrain));
    }
    s.installedLength.assign(s.bonds.size(), 2 * kRadius);
    s.broken.assign(s.bonds.size(), 0);
    s.bondForce.assign(s.bonds.size(), V3{});
    s.bondOffsets.assign(s.n + 1, 0);
    for (const auto& b : s.bonds) {
        ++s.bondOffsets[b[0] + 1];
        ++s.bondOffsets[b[1] + 1];
    }
    for (std::size_t i = 0; i < s.n; ++i)
        s.bondOffsets[i + 1] += s.bondOffsets[i];
    s.bondEntries.resize(s.bondOffsets.back());
    {
        std::vector<std::uint32_t> fill(s.bondOffsets.begin(), s.bondOffsets.end() - 1);
        for (std::uint32_t b = 0; b < s.bonds.size(); ++b) {
            s.bondEntries[fill[s.bonds[b][0]]++] = 2 * b;
            s.bondEntries[fill[s.bonds[b][1]]++] = 2 * b + 1;
        }
    }
    s.strainNeighbours = neighbourTableFromPairs(s.n, lat.pairs);

    const double meanStrain = o.law == BreakingStrainLaw::Normal
                                  ? o.strainMean
                                  : o.weibullScale * std::tgamma(1.0 + 1.0 / o.weibullShape);
    const double bondStrength = kStiffness * meanStrain * 2 * kRadius;
    s.g = o.gravityRatio * bondStrength / (o.rows * kMass);
    s.dt = o.dtFactor * std::sqrt(kMass / kStiffness);
    // Pair dashpot: a fraction of critical damping for the reduced mass m/2.
    s.bondDashpot = o.dashpotRatio * 2.0 * std::sqrt(kStiffness * kMass / 2.0);

    // Steps of the extension: reach the final displacement, then split them into frames.
    const double ramp = kRampSteps * s.dt;
    const double extTime = o.extension * s.length / o.velocity + ramp / 2;
    const auto extSteps = static_cast<std::int64_t>(std::ceil(extTime / s.dt));
    s.frameInterval =
        o.frames > 1 ? std::max<std::int64_t>(1, (extSteps + o.frames - 2) / (o.frames - 1)) : 1;
    s.arena.execute([&] { s.buildContacts(); });
    if (o.settleSteps == 0)
        s.installBonds();
}

ExtensionModel::~ExtensionModel() = default;

std::size_t ExtensionModel::sphereCount() const { return m->n; }
std::size_t ExtensionModel::bondCount() const { return m->bonds.size(); }
std::size_t ExtensionModel::brokenBondCount() const {
    return static_cast<std::size_t>(std::count(m->broken.begin(), m->broken.end(), 1));
}
std::int64_t ExtensionModel::step() const { return m->step; }
std::int64_t ExtensionModel::frameStep(int frame) const {
    return m->opt.settleSteps + frame * m->frameInterval;
}
double ExtensionModel::timeStep() const { return m->dt; }
double ExtensionModel::gravity() const { return m->g; }

//-----------------------------------------------------------------------------
// [SECTION] Contacts and bonds
//-----------------------------------------------------------------------------

void ExtensionModel::State::buildContacts() {
    // Cell grid over the current extent, cells one cut-off wide, spheres counting-sorted by cell
    // (stable, so the order within a cell is by index and the lists are deterministic).
    const double cut = 2 * kRadius + kSkin;
    V3 lo = p[0], hi = p[0];
    for (const V3& q : p) {
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    }
    const int nx = std::max(1, static_cast<int>((hi.x - lo.x) / cut) + 1);
    const int ny = std::max(1, static_cast<int>((hi.y - lo.y) / cut) + 1);
    const int nz = std::max(1, static_cast<int>((hi.z - lo.z) / cut) + 1);
    auto cellCoord = [&](double value, double origin, int count) {
        return std::clamp(static_cast<int>((value - origin) / cut), 0, count - 1);
    };
    std::vector<std::uint32_t> cellOf(n);
    std::vector<std::uint32_t> cellStart(static_cast<std::size_t>(nx) * ny * nz + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const int cx = cellCoord(p[i].x, lo.x, nx), cy = cellCoord(p[i].y, lo.y, ny),
                  cz = cellCoord(p[i].z, lo.z, nz);
        cellOf[i] = static_cast<std::uint32_t>((cz * ny + cy) * nx + cx);
        ++cellStart[cellOf[i] + 1];
    }
    for (std::size_t c = 0; c + 1 < cellStart.size(); ++c)
        cellStart[c + 1] += cellStart[c];
    std::vector<std::uint32_t> sorted(n);
    {
        std::vector<std::uint32_t> fill(cellStart.begin(), cellStart.end() - 1);
        for (std::uint32_t i = 0; i < n; ++i)
            sorted[fill[cellOf[i]]++] = i;
    }

    auto visit = [&](std::uint32_t i, auto&& onPair) {
        const int cx = cellCoord(p[i].x, lo.x, nx), cy = cellCoord(p[i].y, lo.y, ny),
                  cz = cellCoord(p[i].z, lo.z, nz);
        for (int z = std::max(0, cz - 1); z <= std::min(nz - 1, cz + 1); ++z)
            for (int y = std::max(0, cy - 1); y <= std::min(ny - 1, cy + 1); ++y)
                for (int x = std::max(0, cx - 1); x <= std::min(nx - 1, cx + 1); ++x) {
                    const std::size_t c = (static_cast<std::size_t>(z) * ny + y) * nx + x;
                    for (std::uint32_t k = cellStart[c]; k < cellStart[c + 1]; ++k) {
                        const std::uint32_t j = sorted[k];
                        if (j == i ||
                            (kind[i] == SphereKind::Basal && kind[j] == SphereKind::Basal))
                            continue;
                        const V3 d = p[j] - p[i];
                        if (dot(d, d) < cut * cut)
                            onPair(j);
                    }
                }
    };
    std::vector<std::uint32_t> counts(n + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(n), kGrain),
                      [&](const auto& r) {
                          for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
                              std::uint32_t c = 0;
                              if (kind[i] != SphereKind::Basal)
                                  visit(i, [&](std::uint32_t) { ++c; });
                              counts[i + 1] = c;
                          }
                      });
    for (std::size_t i = 0; i < n; ++i)
        counts[i + 1] += counts[i];
    contactOffsets = std::move(counts);
    contactPartner.resize(contactOffsets.back());
    contactBond.resize(contactOffsets.back());
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(n), kGrain),
                      [&](const auto& r) {
                          for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
                              if (kind[i] == SphereKind::Basal)
                                  continue;
                              std::uint32_t at = contactOffsets[i];
                              visit(i, [&](std::uint32_t j) {
                                  std::int32_t bond = -1;
                                  for (std::uint32_t e = bondOffsets[i]; e < bondOffsets[i + 1];
                                       ++e) {
                                      const std::uint32_t b = bondEntries[e] >> 1;
                                      if (bonds[b][0] == j || bonds[b][1] == j) {
                                          bond = static_cast<std::int32_t>(b);
                                          break;
                                      }
                                  }
                                  contactPartner[at] = j;
                                  contactBond[at] = bond;
                                  ++at;
                              });
                          }
                      });
    pBuild = p;
}

// Settled: bonds are cemented at their current lengths (breaking counts stretch from here,
// forces still from the touching distance, so gravity's load stays), and the state becomes
// the reference of strain and of x0 y0 z0.
void ExtensionModel::State::installBonds() {
    for (std::size_t b = 0; b < bonds.size(); ++b) {
        const V3 d = p[bonds[b][1]] - p[bonds[b][0]];
        installedLength[b] = std::sqrt(dot(d, d));
    }
    for (std::size_t i = 0; i < n; ++i)
        reference[i] = {p[i].x, p[i].y, p[i].z};
}

void ExtensionModel::State::computeBondForces() {
    const double k = kStiffness, c = bondDashpot;
    const bool canBreak = step >= opt.settleSteps;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bonds.size(), 4 * kGrain),
                      [&](const auto& r) {
                          for (std::size_t b = r.begin(); b != r.end(); ++b) {
                              if (broken[b]) {
                                  bondForce[b] = {};
                                  continue;
                              }
                              const std::uint32_t i = bonds[b][0], j = bonds[b][1];
                              const V3 d = p[j] - p[i];
                              const double len = std::sqrt(dot(d, d));
                              const double rest = 2 * kRadius;
                              const double stretch = len - rest;
                              if (canBreak && stretch > breakStrain[b] * rest) {
                                  broken[b] = 1;
                                  bondForce[b] = {};
                                  continue;
                              }
                              const V3 nrm = (1.0 / len) * d;
                              const double vn = dot(v[j] - v[i], nrm);
                              // Positive pulls sphere i towards j: tension, or a compressed bond
                              // separating.
                              bondForce[b] = (k * stretch + c * vn) * nrm;
                          }
                      });
}

//-----------------------------------------------------------------------------
// [SECTION] Forces and integration
//-----------------------------------------------------------------------------

void ExtensionModel::State::computeSphereForces(std::vector<V3>& acc) {
    const double k = kStiffness, c = bondDashpot, mu = opt.friction, alpha = opt.localDamping;
    const double reach = 2 * kRadius;
    const double right = boxHi[0] + displacementAt(step);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (kind[i] == SphereKind::Basal) {
                acc[i] = {};
                continue;
            }
            V3 f{0, 0, -kMass * g};
            // Bond forces in the sphere's own fixed order: the sum does not depend on threads.
            for (std::uint32_t e = bondOffsets[i]; e < bondOffsets[i + 1]; ++e) {
                const std::uint32_t entry = bondEntries[e];
                if (entry & 1)
                    f -= bondForce[entry >> 1];
                else
                    f += bondForce[entry >> 1];
            }
            // Frictional contacts of unbonded pairs (never bonded, or bond broken). Coulomb
            // friction without shear history: a tangential dashpot capped at mu * normal force.
            for (std::uint32_t e = contactOffsets[i]; e < contactOffsets[i + 1]; ++e) {
                const std::int32_t b = contactBond[e];
                if (b >= 0 && !broken[static_cast<std::size_t>(b)])
                    continue;
                const std::uint32_t j = contactPartner[e];
                const V3 d = p[j] - p[i];
                const double d2 = dot(d, d);
                if (d2 >= reach * reach)
                    continue;
                const double dist = std::sqrt(d2);
                const V3 nrm = (1.0 / dist) * d;
                const V3 vrel = v[j] - v[i];
                const double vn = dot(vrel, nrm);
                const double fn = std::max(0.0, k * (reach - dist) - c * vn);
                f -= fn * nrm;
                const V3 vt = vrel - vn * nrm;
                const double vtLen = std::sqrt(dot(vt, vt));
                if (vtLen > 1e-12) {
                    const double ft = std::min(mu * fn, c * vtLen);
                    f += (ft / vtLen) * vt;
                }
            }
            // Frictionless walls: x = 0 and the moving right wall, y = 0 and y = top, z = 0.
            const V3 q = p[i], w = v[i];
            // Separation speed is positive when the sphere leaves the wall.
            auto wall = [&](double overlap, double separation, double& component, double sign) {
                if (overlap > 0)
                    component += sign * std::max(0.0, k * overlap - c * separation);
            };
            const double wallSpeed = speedAt(step);
            wall(kRadius - q.x, w.x, f.x, 1.0);
            wall(q.x + kRadius - right, wallSpeed - w.x, f.x, -1.0);
            wall(kRadius - q.y, w.y, f.y, 1.0);
            wall(q.y + kRadius - boxHi[1], -w.y, f.y, -1.0);
            wall(kRadius - q.z, w.z, f.z, 1.0);
            // Local (Cundall) damping: opposes each velocity component with a share of the
            // force, vanishing at equilibrium, so slow loading stays quasi-static.
            // It works on the velocity relative to the base beneath: damping against the fixed
            // frame would drag a moving block back and stretch it.
            auto damp = [&](double fc, double vc) {
                return vc > 0   ? fc - alpha * std::fabs(fc)
                       : vc < 0 ? fc + alpha * std::fabs(fc)
                                : fc;
            };
            acc[i] = {damp(f.x, w.x - baseWeight[i] * wallSpeed) / kMass, damp(f.y, w.y) / kMass,
                      damp(f.z, w.z) / kMass};
        }
    });
}

double ExtensionModel::State::integrate(const std::vector<V3>& acc) {
    const double u = displacementAt(step + 1), speed = speedAt(step + 1);
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, kGrain), 0.0,
        [&](const auto& r, double worst) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                if (kind[i] == SphereKind::Basal) {
                    p[i] = {x0[i].x + baseWeight[i] * u, x0[i].y, x0[i].z};
                    v[i] = {baseWeight[i] * speed, 0, 0};
                } else {
                    v[i] += dt * acc[i];
                    p[i] += dt * v[i];
                    if (kind[i] == SphereKind::Side) {
                        p[i].x = x0[i].x + baseWeight[i] * u;
                        v[i].x = baseWeight[i] * speed;
                    }
                }
                const V3 d = p[i] - pBuild[i];
                worst = std::max(worst, dot(d, d));
            }
            return worst;
        },
        [](double a, double b) { return std::max(a, b); });
}

//-----------------------------------------------------------------------------
// [SECTION] Advancing and snapshots
//-----------------------------------------------------------------------------

void ExtensionModel::advance(std::int64_t steps) {
    State& s = *m;
    std::vector<V3> acc(s.n);
    s.arena.execute([&] {
        for (std::int64_t k = 0; k < steps; ++k) {
            // Velocity Verlet with the two half kicks of consecutive steps fused (leapfrog):
            // forces from positions x(n) and velocities v(n - 1/2), then kick and drift.
            s.computeBondForces();
            s.computeSphereForces(acc);
            const double worst = s.integrate(acc);
            ++s.step;
            if (s.step == s.opt.settleSteps)
                s.installBonds();
            if (worst > 0.25 * kSkin * kSkin)
                s.buildContacts();
        }
    });
}

Frame ExtensionModel::snapshot() const {
    const State& s = *m;
    std::vector<std::array<double, 3>> current(s.n);
    for (std::size_t i = 0; i < s.n; ++i)
        current[i] = {s.p[i].x, s.p[i].y, s.p[i].z};
    std::vector<double> strain;
    std::vector<std::int32_t> brokenPerSphere(s.n, 0);
    s.arena.execute(
        [&] { strain = vonMisesShearStrain(s.reference, current, s.strainNeighbours); });
    for (std::size_t i = 0; i < s.n; ++i)
        for (std::uint32_t e = s.bondOffsets[i]; e < s.bondOffsets[i + 1]; ++e)
            brokenPerSphere[i] += s.broken[s.bondEntries[e] >> 1];

    // Values are rounded (positions to 1e-3 radii, strain to 1e-4) so the dump stays compact:
    // the writer prints the shortest text that reads back to the same float.
    Frame f;
    f.timestep = s.step;
    f.ids.resize(s.n);
    f.x.resize(s.n);
    f.y.resize(s.n);
    f.z.resize(s.n);
    f.radius.assign(s.n, static_cast<float>(kRadius));
    std::vector<std::int32_t> type(s.n), layer(s.n);
    std::vector<float> strainF(s.n), ix(s.n), iy(s.n), iz(s.n);
    for (std::size_t i = 0; i < s.n; ++i) {
        f.ids[i] = static_cast<std::int64_t>(i) + 1;
        f.x[i] = static_cast<float>(quantize(s.p[i].x, 1e-3));
        f.y[i] = static_cast<float>(quantize(s.p[i].y, 1e-3));
        f.z[i] = static_cast<float>(quantize(s.p[i].z, 1e-3));
        type[i] = static_cast<std::int32_t>(s.kind[i]) + 1;
        layer[i] = s.band[i];
        strainF[i] = static_cast<float>(quantize(strain[i], 1e-4));
        ix[i] = static_cast<float>(quantize(s.reference[i][0], 1e-3));
        iy[i] = static_cast<float>(quantize(s.reference[i][1], 1e-3));
        iz[i] = static_cast<float>(quantize(s.reference[i][2], 1e-3));
    }
    auto ints = [](std::string name, std::vector<std::int32_t>&& values) {
        AttributeColumn c;
        c.name = std::move(name);
        c.type = ColumnType::Int32;
        c.ints = std::move(values);
        return c;
    };
    auto floats = [](std::string name, std::vector<float>&& values) {
        AttributeColumn c;
        c.name = std::move(name);
        c.type = ColumnType::Float32;
        c.floats = std::move(values);
        return c;
    };
    f.attributes.push_back(ints("type", std::move(type)));
    f.attributes.push_back(floats("strain", std::move(strainF)));
    f.attributes.push_back(ints("broken_bonds", std::move(brokenPerSphere)));
    f.attributes.push_back(ints("layer", std::move(layer)));
    f.attributes.push_back(floats("x0", std::move(ix)));
    f.attributes.push_back(floats("y0", std::move(iy)));
    f.attributes.push_back(floats("z0", std::move(iz)));
    f.box.known = true;
    f.box.lo = {0, 0, 0};
    f.box.hi = {quantize(s.boxHi[0] + s.displacementAt(s.step), 1e-3), quantize(s.boxHi[1], 1e-3),
                quantize(s.boxHi[2], 1e-3)};
    f.finalize();
    return f;
}

ExtensionRunStats runExtensionModel(const ExtensionModelOptions& options, const FrameSink& sink,
                                    const ProgressCallback& progress) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    ExtensionModel model(options);
    ExtensionRunStats stats;
    stats.spheres = model.sphereCount();
    stats.bonds = model.bondCount();
    const std::int64_t total = model.frameStep(options.frames - 1);
    double simSeconds = 0;
    auto report = [&] {
        if (progress && !progress(static_cast<double>(model.step()) / static_cast<double>(total)))
            throw GenerationCancelled();
    };
    report();
    for (int frame = 0; frame < options.frames; ++frame) {
        const std::int64_t target = model.frameStep(frame);
        while (model.step() < target) {
            const std::int64_t chunk = std::min<std::int64_t>(target - model.step(), 250);
            const auto t0 = Clock::now();
            model.advance(chunk);
            simSeconds += std::chrono::duration<double>(Clock::now() - t0).count();
            report();
        }
        if (sink)
            sink(model.snapshot(), frame);
        ++stats.frames;
    }
    stats.steps = model.step();
    stats.brokenBonds = model.brokenBondCount();
    stats.simulationSeconds = simSeconds;
    stats.totalSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    return stats;
}

} // namespace faultline::core
