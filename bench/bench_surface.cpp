// Fault surface speed (issue 8), all on the same spheres in one run:
//  - 50,000 spheres, voxel = r/2, inverse-square at the default tolerance: field + colour + mesh,
//    against OpenVDB's ParticlesToLevelSet + volumeToMesh at the same voxel size;
//  - the compact kernel on the same set; re-meshing at a new iso-value;
//  - 2,000 spheres: the paper's Algorithm 1 (dense grid, every sphere against every voxel)
//    against the multilevel field, with the largest disagreement reported as a counter: value
//    only with inverse-square, and as the paper has it (r/d, value and gradient);
//  - 26,000 spheres at voxel 0.5 (the ParaView comparison in the issue).
#include "bench/fault_zone.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/session.hpp"
#include "core/surface/fault_surface.hpp"
#include "core/surface/metaball_field.hpp"
#include "core/surface/metaball_reference.hpp"
#include "core/surface/surface_cache.hpp"
#include "core/surface/surface_plan.hpp"

#include <benchmark/benchmark.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <sys/resource.h>
#include <utility>
#include <vector>

namespace fb = faultline::bench;
namespace fc = faultline::core;

namespace {

constexpr float kRadius = 0.5f;
constexpr float kThickness = 4.0f;

const fb::FaultZone& zone(std::size_t count) {
    static std::map<std::size_t, fb::FaultZone> zones;
    auto it = zones.find(count);
    if (it == zones.end())
        it = zones.emplace(count, fb::hcpFaultZone(count, kRadius, kThickness)).first;
    return it->second;
}

// The iso-value whose surface passes one radius... one unit outside the zone's middle.
float isoOneUnitOutside(const fb::FaultZone& z, fc::MetaballKernel kernel) {
    const double dip = 60.0 * 3.14159265358979 / 180.0;
    const double d = kThickness / 2 + 1.0;
    fc::SurfaceParams p;
    p.kernel = kernel;
    return static_cast<float>(
        fc::referenceSample(z.set(), p, {0.3, d * std::sin(dip), d * std::cos(dip)}).value);
}

fc::SurfaceParams params(const fb::FaultZone& z, fc::MetaballKernel kernel, float voxel) {
    fc::SurfaceParams p;
    p.kernel = kernel;
    p.voxelSize = voxel;
    p.iso = kernel == fc::MetaballKernel::Compact ? 0.5f : isoOneUnitOutside(z, kernel);
    return p;
}

void report(benchmark::State& state, const fc::SurfaceResult& r) {
    const auto& s = r.field->stats();
    state.counters["blocks"] = double(s.blocks);
    state.counters["voxels"] = double(s.activeVoxels);
    state.counters["levels"] = s.levels;
    state.counters["charge_levels"] = s.anterpolatedLevels;
    state.counters["coarse_nodes"] = double(s.coarseNodes);
    state.counters["triangles"] = double(r.mesh.triangleCount());
    state.counters["plan_ms"] = 1e3 * s.planSeconds;
    state.counters["field_ms"] = 1e3 * s.fieldSeconds;
    state.counters["levels_ms"] = 1e3 * s.levelsSeconds;
    state.counters["blocks_ms"] = 1e3 * s.blocksSeconds;
    state.counters["color_ms"] = 1e3 * s.colorSeconds;
    state.counters["mesh_ms"] = 1e3 * s.meshSeconds;
    state.counters["iso"] = r.iso;
    state.counters["kappa"] = s.kappa;
    state.counters["a0"] = s.nearCutoff;
    state.counters["est_err_over_iso"] = s.estimatedError / r.iso;
}

void BM_Surface(benchmark::State& state, fc::MetaballKernel kernel, std::size_t count,
                float voxel) {
    const auto& z = zone(count);
    const auto p = params(z, kernel, voxel);
    fc::SurfaceResult last;
    for (auto _ : state)
        last = fc::buildSurface(z.set(), p);
    report(state, last);
}

struct ZoneParticles {
    using PosType = openvdb::Vec3R;
    const fb::FaultZone* z;
    std::size_t size() const { return z->x.size(); }
    void getPos(std::size_t n, openvdb::Vec3R& p) const { p = {z->x[n], z->y[n], z->z[n]}; }
    void getPosRad(std::size_t n, openvdb::Vec3R& p, openvdb::Real& r) const {
        getPos(n, p);
        r = z->radius[n];
    }
};

// OpenVDB's way to the same surface: the spheres rasterised as a narrow-band level set, then
// meshed at 0. Counters: quads and active voxels of the last run.
struct OpenVdbSurface {
    openvdb::FloatGrid::Ptr grid;
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec4I> polys;
    double meshMs = 0.0; // volumeToMesh's part of the time
};

OpenVdbSurface openVdbOnce(const ZoneParticles& particles, float voxel) {
    openvdb::initialize();
    OpenVdbSurface s;
    s.grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, 3.0);
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*s.grid);
    raster.rasterizeSpheres(particles);
    raster.finalize(true);
    const auto t0 = std::chrono::steady_clock::now();
    openvdb::tools::volumeToMesh(*s.grid, s.points, s.polys, 0.0);
    s.meshMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

void openVdbLevelSetAndMesh(benchmark::State& state, const ZoneParticles& particles, float voxel) {
    std::size_t quads = 0, voxels = 0;
    for (auto _ : state) {
        const OpenVdbSurface s = openVdbOnce(particles, voxel);
        quads = s.polys.size();
        voxels = s.grid->activeVoxelCount();
    }
    state.counters["quads"] = double(quads);
    state.counters["voxels"] = double(voxels);
}

void BM_OpenVdbParticlesToLevelSetAndMesh(benchmark::State& state, std::size_t count, float voxel) {
    openVdbLevelSetAndMesh(state, ZoneParticles{&zone(count)}, voxel);
}

void BM_Remesh(benchmark::State& state, std::size_t count, float voxel, fc::NormalSource normals) {
    const auto& z = zone(count);
    const auto p = params(z, fc::MetaballKernel::InverseSquare, voxel);
    const auto built = fc::buildSurface(z.set(), p);
    const float iso = p.iso * 1.05f;
    fc::SurfaceMesh mesh;
    for (auto _ : state)
        mesh = fc::remesh(*built.field, iso, nullptr, normals);
    state.counters["triangles"] = double(mesh.triangleCount());
}

// Algorithm 1 on the dense box around every evaluated block; the counter is the largest
// |multilevel - Algorithm 1| over the kept voxels as a fraction of the iso-value. Without
// `gradient` only the value at each voxel: a stricter baseline than Algorithm 1 itself, which
// also takes the gradient (line 8) at every point.
void BM_Algorithm1Dense(benchmark::State& state, fc::MetaballKernel kernel, std::size_t count,
                        float voxel, bool gradient) {
    const auto& z = zone(count);
    const auto p = params(z, kernel, voxel);
    fc::MetaballField field(z.set(), p, voxel);
    const auto plan = fc::planSurface(field, p.iso / p.isoRangeFactor, p.iso * p.isoRangeFactor,
                                      p.memoryBudgetBytes, nullptr);
    std::array<int, 3> lo{1 << 30, 1 << 30, 1 << 30}, hi{-(1 << 30), -(1 << 30), -(1 << 30)};
    for (const auto& b : plan.blocks)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b[k]);
            hi[k] = std::max(hi[k], b[k] + 7);
        }
    const std::array<int, 3> dims{hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
    std::vector<float> dense;
    std::vector<std::array<float, 3>> gradients;
    for (auto _ : state)
        dense = fc::algorithm1Dense(z.set(), p, lo, dims, voxel, gradient ? &gradients : nullptr);
    field.prepare(plan.blocks, nullptr);
    double worst = 0.0;
    const double clamp = 4.0 * p.iso * p.isoRangeFactor;
    float density[fc::kBlockVoxels];
    fc::Vec3f color[fc::kBlockVoxels];
    for (const auto& b : plan.blocks) {
        field.evaluateBlock(b, density, color);
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j)
                for (int k = 0; k < 8; ++k) {
                    const std::size_t at =
                        (std::size_t(b[2] + k - lo[2]) * dims[1] + (b[1] + j - lo[1])) * dims[0] +
                        (b[0] + i - lo[0]);
                    const double e =
                        std::abs(std::min<double>(density[fc::blockOffset(i, j, k)], clamp) -
                                 std::min<double>(dense[at], clamp));
                    worst = std::max(worst, e);
                }
    }
    state.counters["dense_voxels"] = double(dense.size());
    state.counters["kept_voxels"] = double(plan.blocks.size() * fc::kBlockVoxels);
    state.counters["max_err_over_iso"] = worst / p.iso;
}

// The 50k set's field against Algorithm 1 on a sample of the planned blocks (every 64th): the
// largest disagreement as a fraction of the iso-value, at the size the issue's speed target uses.
// Largest |field - Algorithm 1| over every voxel of every stride-th planned block, over the iso.
void sampledError(benchmark::State& state, const fb::FaultZone& z, const fc::SurfaceParams& p,
                  float voxel, std::size_t stride) {
    double worst = 0.0, estimate = 0.0;
    std::size_t sampled = 0;
    for (auto _ : state) {
        fc::MetaballField field(z.set(), p, voxel);
        const auto plan = fc::planSurface(field, p.iso / p.isoRangeFactor, p.iso * p.isoRangeFactor,
                                          p.memoryBudgetBytes, nullptr);
        field.prepare(plan.blocks, nullptr);
        estimate = field.estimatedError();
        const double clamp = 4.0 * p.iso * p.isoRangeFactor;
        float density[fc::kBlockVoxels];
        for (std::size_t b = 0; b < plan.blocks.size(); b += stride, ++sampled) {
            const auto& o = plan.blocks[b];
            field.evaluateBlock(o, density, nullptr);
            const auto dense = fc::algorithm1Dense(z.set(), p, o, {8, 8, 8}, voxel);
            for (int i = 0; i < 8; ++i)
                for (int j = 0; j < 8; ++j)
                    for (int k = 0; k < 8; ++k) {
                        const double e = std::abs(
                            std::min<double>(density[fc::blockOffset(i, j, k)], clamp) -
                            std::min<double>(dense[(std::size_t(k) * 8 + j) * 8 + i], clamp));
                        worst = std::max(worst, e);
                    }
        }
    }
    state.counters["sampled_blocks"] = double(sampled);
    state.counters["max_err_over_iso"] = worst / p.iso;
    state.counters["est_err_over_iso"] = estimate / p.iso;
}

void BM_SampledErrorAgainstAlgorithm1(benchmark::State& state, std::size_t count, float voxel) {
    const auto& z = zone(count);
    sampledError(state, z, params(z, fc::MetaballKernel::InverseSquare, voxel), voxel, 64);
}

// The spread-out selection (issue 23): about 10k spheres of three fault zones across a whole
// 200 x 130 x 110 block, at the wrapping iso (what a new surface in the workbench and a journal's
// surface.build without iso use), voxel = r / divisor. Peak RSS of the process is reported too:
// run one case per process (--benchmark_filter) for a figure of that case alone.
const fb::FaultZone& spread() {
    static const fb::FaultZone z = fb::spreadFaultZones(10000);
    return z;
}

// The spread-out set's parameters: a kernel at voxel r / divisor and the wrapping iso.
fc::SurfaceParams spreadParams(fc::MetaballKernel kernel, float divisor) {
    fc::SurfaceParams p;
    p.kernel = kernel;
    p.voxelSize = 1.0f / divisor;
    p.iso = static_cast<float>(fc::wrappingIso(spread().set(), p));
    return p;
}

double peakRssMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

void BM_SpreadSurface(benchmark::State& state, fc::MetaballKernel kernel, float divisor) {
    const auto& z = spread();
    const fc::SurfaceParams p = spreadParams(kernel, divisor);
    fc::SurfaceResult last;
    for (auto _ : state) {
        last = {}; // one surface at a time, as the peak memory counts it
        last = fc::buildSurface(z.set(), p);
    }
    report(state, last);
    state.counters["spheres"] = double(z.x.size());
    state.counters["peak_rss_mb"] = peakRssMiB();
}

// Re-meshing the spread-out r/d surface at r/2 at the edges of its iso range (the iso slider).
void BM_SpreadRemesh(benchmark::State& state) {
    const auto& z = spread();
    const fc::SurfaceParams p = spreadParams(fc::MetaballKernel::Inverse, 2.0f);
    const auto built = fc::buildSurface(z.set(), p);
    fc::SurfaceMesh mesh;
    bool up = false;
    for (auto _ : state) {
        up = !up;
        mesh = fc::remesh(*built.field, up ? built.field->isoMax() : built.field->isoMin());
    }
    state.counters["triangles"] = double(mesh.triangleCount());
}

// The spread-out r/2 case's field object and block plan alone (the fold planner).
void BM_SpreadPlan(benchmark::State& state, fc::MetaballKernel kernel) {
    const auto& z = spread();
    const fc::SurfaceParams p = spreadParams(kernel, 2.0f);
    std::size_t blocks = 0;
    for (auto _ : state) {
        fc::MetaballField field(z.set(), p, p.voxelSize);
        const auto plan = fc::planSurface(field, p.iso / p.isoRangeFactor, p.iso * p.isoRangeFactor,
                                          p.memoryBudgetBytes, nullptr);
        blocks = plan.blocks.size();
    }
    state.counters["blocks"] = double(blocks);
}

// The spread-out r/2 case's field against Algorithm 1 on every 37th planned block (about 400
// to 550 blocks, each voxel summed over all 10k spheres): the accuracy the speed is bought with.
void BM_SpreadSampledError(benchmark::State& state, fc::MetaballKernel kernel) {
    const fc::SurfaceParams p = spreadParams(kernel, 2.0f);
    sampledError(state, spread(), p, p.voxelSize, 37);
}

// The issue's ratios, robust to a machine whose speed drifts between benchmarks: rounds of
// OpenVDB, then each Faultline build, on the same spheres at one voxel size; counters are the
// medians of each one's times (name_ms) and of the per-round ratios (ratio_name). Each build is
// timed without freeing its result (freed after the clock stops). Also each one's meshing part
// (openvdb_mesh_ms: volumeToMesh; name_mesh_ms: surface nets), to tell the fields' cost apart.
void ratioRounds(benchmark::State& state, const fb::FaultZone& z, float voxel,
                 const std::vector<std::pair<std::string, fc::SurfaceParams>>& builds) {
    const ZoneParticles particles{&z};
    constexpr int kRounds = 7;
    std::vector<double> vdb, vdbMesh;
    std::vector<std::vector<double>> ours(builds.size()), ratio(builds.size()),
        oursMesh(builds.size());
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point t0) {
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    for (auto _ : state)
        for (int round = 0; round < kRounds; ++round) {
            auto t0 = Clock::now();
            OpenVdbSurface theirs = openVdbOnce(particles, voxel);
            vdb.push_back(ms(t0));
            vdbMesh.push_back(theirs.meshMs);
            for (std::size_t k = 0; k < builds.size(); ++k) {
                t0 = Clock::now();
                fc::SurfaceResult built = fc::buildSurface(z.set(), builds[k].second);
                ours[k].push_back(ms(t0));
                oursMesh[k].push_back(1e3 * built.field->stats().meshSeconds);
                ratio[k].push_back(ours[k].back() / vdb.back());
            }
        }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    state.counters["openvdb_ms"] = median(vdb);
    state.counters["openvdb_min_ms"] = *std::min_element(vdb.begin(), vdb.end());
    state.counters["openvdb_mesh_ms"] = median(vdbMesh);
    for (std::size_t k = 0; k < builds.size(); ++k) {
        state.counters[builds[k].first + "_ms"] = median(ours[k]);
        state.counters[builds[k].first + "_mesh_ms"] = median(oursMesh[k]);
        state.counters["ratio_" + builds[k].first] = median(ratio[k]);
    }
}

// The spread-out set, both kernels at the wrapping iso.
void BM_SpreadRatio(benchmark::State& state, float divisor) {
    const auto& z = spread();
    std::vector<std::pair<std::string, fc::SurfaceParams>> builds;
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare})
        builds.emplace_back(kernel == fc::MetaballKernel::Inverse ? "inverse" : "inverse_square",
                            spreadParams(kernel, divisor));
    ratioRounds(state, z, 1.0f / divisor, builds);
}

// The compact zone (BM_Surface's inverse_square_50k against openvdb_50k).
void BM_CompactRatio(benchmark::State& state, std::size_t count, float voxel) {
    const auto& z = zone(count);
    ratioRounds(state, z, voxel,
                {{"inverse_square", params(z, fc::MetaballKernel::InverseSquare, voxel)}});
}

void BM_SpreadOpenVdb(benchmark::State& state, float divisor) {
    openVdbLevelSetAndMesh(state, ZoneParticles{&spread()}, 1.0f / divisor);
    state.counters["peak_rss_mb"] = peakRssMiB();
}

//-----------------------------------------------------------------------------
// Issue 40: the whole op on the selections users make, against OpenVDB.
//-----------------------------------------------------------------------------

// A session holding one selection as fault "F1" in the current frame, as a user builds its
// surface: the data opened, a threshold, fault.create from the visible spheres.
struct OpCase {
    std::unique_ptr<fc::Session> session;
    fb::FaultZone spheres; // F1's spheres (for OpenVDB)
    double meanRadius = 0.0;
    std::string error; // why the case cannot run here
};

std::string benchDir() {
    const auto dir = std::filesystem::temp_directory_path() / "faultline-bench-surface";
    std::filesystem::create_directories(dir);
    return dir.string();
}

// The 525k-sphere block of spreadFaultZones (HCP, radius 1, 200 x 130 x 110) as a LAMMPS dump
// with each sphere's distance to the nearest of the three zones' mid-planes ("zone_distance"),
// which a threshold cuts as one on strain would: every sphere of a zone about a diameter thick.
std::string writeZonesBlock() {
    const std::string path = benchDir() + "/zones525k.lammpstrj";
    if (std::filesystem::exists(path))
        return path;
    std::string body;
    std::size_t n = 0;
    char line[160];
    fb::forEachFaultedBlockSphere([&](const double* p, const double* across) {
        const double dist =
            std::min({std::abs(across[0]), std::abs(across[1]), std::abs(across[2])});
        ++n;
        std::snprintf(line, sizeof line, "%zu %.4f %.4f %.4f 1 %.4f\n", n, p[0], p[1], p[2], dist);
        body += line;
    });
    std::ofstream out(path + ".part", std::ios::binary);
    out << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n"
        << n
        << "\nITEM: BOX BOUNDS ff ff ff\n0 202\n0 132\n0 112\nITEM: ATOMS id x y z radius "
           "zone_distance\n"
        << body;
    out.close();
    std::filesystem::rename(path + ".part", path);
    return path;
}

// A fault zone as a LAMMPS dump of its spheres alone (the sparse spread and compact cases).
std::string writeZone(const fb::FaultZone& z, const std::string& name) {
    const std::string path = benchDir() + "/" + name + ".lammpstrj";
    if (std::filesystem::exists(path))
        return path;
    std::ofstream out(path, std::ios::binary);
    out << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n"
        << z.x.size() << "\nITEM: ATOMS id x y z radius\n";
    char line[128];
    for (std::size_t i = 0; i < z.x.size(); ++i) {
        std::snprintf(line, sizeof line, "%zu %.5f %.5f %.5f %.5f\n", i + 1, z.x[i], z.y[i], z.z[i],
                      z.radius[i]);
        out << line;
    }
    return path;
}

OpCase openCase(const std::string& name) {
    OpCase c;
    c.session = std::make_unique<fc::Session>();
    auto& s = *c.session;
    try {
        if (name == "zones525k") {
            s.apply({{"op", "data.open"}, {"paths", {writeZonesBlock()}}});
            s.apply(fc::Json::parse(
                R"({"op":"threshold.add","variable":"zone_distance","low":0,"high":0.6})"));
        } else if (name == "demo_bb3") {
            const char* home = std::getenv("HOME");
            const std::string demo = std::string(home ? home : "") +
                                     "/.local/share/faultline/demo/block-v2.lammpstrj.gz";
            if (!std::filesystem::exists(demo)) {
                c.error = "no demo: run faultline generate --demo";
                return c;
            }
            s.apply({{"op", "data.open"}, {"paths", {demo}}});
            s.apply({{"op", "frame.set"}, {"frame", s.dataset()->frameCount() - 1}});
            s.apply(fc::Json::parse(
                R"({"op":"threshold.add","variable":"broken_bonds","low":3,"high":1e30})"));
        } else if (name == "lammps_bands") {
            // The real LAMMPS extension run's shear bands (tests/replay/lammps_extension_strain).
            const std::string run = std::string(FAULTLINE_SOURCE_DIR) +
                                    "/tests/data/real_runs/lammps/dump.extension.gz";
            s.apply({{"op", "data.open"}, {"paths", {run}}});
            s.apply(fc::Json::parse(R"({"op":"frame.set","frame":4})"));
            s.apply(fc::Json::parse(R"({"op":"strain.add","since_offset":-1,"prefix":"inc_"})"));
            s.apply(fc::Json::parse(
                R"({"op":"threshold.add","variable":"inc_shear_strain","low":0.15,"high":1e30})"));
        } else if (name == "sparse_spread") {
            s.apply({{"op", "data.open"}, {"paths", {writeZone(spread(), "spread10k")}}});
        } else if (name == "compact_50k") {
            s.apply({{"op", "data.open"}, {"paths", {writeZone(zone(50000), "compact50k")}}});
        } else {
            c.error = "unknown case " + name;
            return c;
        }
        s.apply(fc::Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
        const fc::Fault* f = s.state().fault("F1");
        const fc::FaultSpheres fs = fc::gatherFaultSpheres(*s.currentFrame(), *f);
        c.spheres.x = fs.x, c.spheres.y = fs.y, c.spheres.z = fs.z, c.spheres.radius = fs.radius;
        c.spheres.rgb = fs.rgb;
        double sum = 0.0;
        for (float r : fs.radius)
            sum += r;
        c.meanRadius = fs.radius.empty() ? 1.0 : sum / double(fs.radius.size());
    } catch (const std::exception& e) {
        c.error = e.what();
    }
    return c;
}

OpCase& opCase(const std::string& name) {
    static std::map<std::string, OpCase> cases;
    auto it = cases.find(name);
    if (it == cases.end())
        it = cases.emplace(name, openCase(name)).first;
    return it->second;
}

// The case, or null with the benchmark skipped saying why.
OpCase* readyCase(benchmark::State& state, const char* name) {
    OpCase& c = opCase(name);
    if (!c.error.empty()) {
        state.SkipWithError(c.error.c_str());
        return nullptr;
    }
    return &c;
}

// surface.build on F1 as a user runs it (the wrapping iso, the default iso-slider range, the
// fault's colour), both kernels at voxel = mean radius / divisor, against OpenVDB's
// ParticlesToLevelSet + volumeToMesh on the same spheres at the same voxel, interleaved rounds
// (medians; the ratio's smallest and largest round too). Counters: each one's ms and ratio, the
// phases of one build (wrapping iso, plan, coarse levels, blocks, colour, mesh), the spheres,
// whether the planner saw a sparse set, and the process's peak RSS growth over the first build
// of each kernel (run one case per process for a figure of that case alone).
void BM_SurfaceOpRatio(benchmark::State& state, const char* name, float divisor) {
    OpCase* found = readyCase(state, name);
    if (!found)
        return;
    OpCase& c = *found;
    fc::Session& s = *c.session;
    const float voxel = float(c.meanRadius / divisor);
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point t0) {
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    // FAULTLINE_BENCH_KERNEL=inverse or inverse-square: that kernel alone (for a profile of it).
    std::vector<std::pair<const char*, const char*>> kernels = {
        {"inverse", "inverse"}, {"inverse_square", "inverse-square"}};
    if (const char* only = std::getenv("FAULTLINE_BENCH_KERNEL"))
        std::erase_if(kernels, [&](const auto& k) { return std::string(k.second) != only; });
    auto buildOp = [&](const char* kernel) {
        // A whole build each time: not the surface the session kept from the last round.
        s.surfaceCache().clear();
        s.apply({{"op", "surface.build"}, {"fault", "F1"}, {"kernel", kernel}, {"voxel", voxel}});
    };
    // Phases of one build per kernel, and the memory it takes.
    for (const auto& [key, kernel] : kernels) {
        const double before = peakRssMiB();
        auto t0 = Clock::now();
        buildOp(kernel);
        state.counters[std::string(key) + "_first_ms"] = ms(t0);
        state.counters[std::string(key) + "_peak_rss_growth_mb"] = peakRssMiB() - before;
        const fc::SurfaceSettings st = *s.state().surface("F1");
        const fc::Fault formed =
            fc::faultAsFormed(*s.currentFrame(), *s.state().fault("F1"), s.state().thresholds);
        t0 = Clock::now();
        (void)fc::faultWrappingIso(*s.currentFrame(), formed, st);
        state.counters[std::string(key) + "_wrap_iso_ms"] = ms(t0);
        // FAULTLINE_BENCH_PHASE_RUNS=n: each phase's fastest of n builds (the machine's speed
        // drifts by more than a change to one phase saves).
        const int phaseRuns = std::max(1, std::atoi(std::getenv("FAULTLINE_BENCH_PHASE_RUNS")
                                                        ? std::getenv("FAULTLINE_BENCH_PHASE_RUNS")
                                                        : "1"));
        fc::SurfaceResult r;
        double phases[5] = {1e30, 1e30, 1e30, 1e30, 1e30};
        double direct = 1e30;
        for (int run = 0; run < phaseRuns; ++run) {
            const auto tDirect = Clock::now();
            r = fc::buildFaultSurface(*s.currentFrame(), {formed, st});
            direct = std::min(direct, ms(tDirect));
            const auto& stats = r.field->stats();
            const double now[5] = {stats.planSeconds, stats.levelsSeconds, stats.blocksSeconds,
                                   stats.colorSeconds, stats.meshSeconds};
            for (int p = 0; p < 5; ++p)
                phases[p] = std::min(phases[p], now[p]);
        }
        const auto& stats = r.field->stats();
        const std::string k(key);
        state.counters[k + "_plan_ms"] = 1e3 * phases[0];
        state.counters[k + "_levels_ms"] = 1e3 * phases[1];
        state.counters[k + "_blocks_ms"] = 1e3 * phases[2];
        state.counters[k + "_color_ms"] = 1e3 * phases[3];
        state.counters[k + "_mesh_ms"] = 1e3 * phases[4];
        state.counters[k + "_build_ms"] = direct; // buildFaultSurface alone, no op around it
        state.counters[k + "_blocks"] = double(stats.blocks);
        state.counters[k + "_triangles"] = double(r.mesh.triangleCount());
        state.counters[k + "_sparse"] =
            fc::MetaballField(c.spheres.set(), r.field->params(), voxel).sparse();
    }
    const ZoneParticles particles{&c.spheres};
    // Seven by default: the median of three rounds moved by a third between runs of the
    // cases near 2x on a 2-core machine whose speed drifts.
    const int rounds = std::max(1, std::atoi(std::getenv("FAULTLINE_BENCH_ROUNDS")
                                                 ? std::getenv("FAULTLINE_BENCH_ROUNDS")
                                                 : "7"));
    std::vector<double> vdb;
    std::map<std::string, std::vector<double>> ours, ratio;
    for (auto _ : state)
        for (int round = 0; round < rounds; ++round) {
            auto t0 = Clock::now();
            { const OpenVdbSurface theirs = openVdbOnce(particles, voxel); }
            vdb.push_back(ms(t0));
            for (const auto& [key, kernel] : kernels) {
                t0 = Clock::now();
                buildOp(kernel);
                ours[key].push_back(ms(t0));
                ratio[key].push_back(ours[key].back() / vdb.back());
            }
        }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    state.counters["spheres"] = double(c.spheres.x.size());
    state.counters["voxel"] = voxel;
    state.counters["openvdb_ms"] = median(vdb);
    state.counters["openvdb_min_ms"] = *std::min_element(vdb.begin(), vdb.end());
    for (const auto& [key, kernel] : kernels) {
        state.counters[std::string(key) + "_ms"] = median(ours[key]);
        state.counters["ratio_" + std::string(key)] = median(ratio[key]);
        // The rounds' spread: a case at the edge of its target shows it here.
        state.counters[std::string(key) + "_min_ms"] =
            *std::min_element(ours[key].begin(), ours[key].end());
        const auto [lo, hi] = std::minmax_element(ratio[key].begin(), ratio[key].end());
        state.counters["ratio_" + std::string(key) + "_min"] = *lo;
        state.counters["ratio_" + std::string(key) + "_max"] = *hi;
    }
    state.counters["peak_rss_mb"] = peakRssMiB();
}

// The accuracy the op's speed is bought with, on the same selections: the field against
// Algorithm 1 on every stride-th planned block, both kernels at the wrapping iso.
void BM_SurfaceOpSampledError(benchmark::State& state, const char* name, float divisor,
                              fc::MetaballKernel kernel, int stride) {
    OpCase* found = readyCase(state, name);
    if (!found)
        return;
    OpCase& c = *found;
    fc::Session& s = *c.session;
    const float voxel = float(c.meanRadius / divisor);
    s.apply({{"op", "surface.build"},
             {"fault", "F1"},
             {"kernel", std::string(fc::kernelName(kernel))},
             {"voxel", voxel}});
    const fc::Fault formed =
        fc::faultAsFormed(*s.currentFrame(), *s.state().fault("F1"), s.state().thresholds);
    const fc::SurfaceParams p = fc::surfaceParamsOf(*s.state().surface("F1"), formed);
    sampledError(state, c.spheres, p, voxel, stride);
}

} // namespace

BENCHMARK_CAPTURE(BM_Surface, inverse_square_50k, fc::MetaballKernel::InverseSquare, 50000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_OpenVdbParticlesToLevelSetAndMesh, openvdb_50k, 50000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Surface, compact_50k, fc::MetaballKernel::Compact, 50000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Remesh, inverse_square_50k_analytic_normals, 50000, 0.25f,
                  fc::NormalSource::Analytic)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Remesh, inverse_square_50k_grid_normals, 50000, 0.25f, fc::NormalSource::Grid)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Surface, inverse_square_2k, fc::MetaballKernel::InverseSquare, 2000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_Algorithm1Dense, inverse_square_2k, fc::MetaballKernel::InverseSquare, 2000,
                  0.25f, false)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
// The paper's own kernel (r/d) with the gradient Algorithm 1 takes at every point.
BENCHMARK_CAPTURE(BM_Surface, inverse_2k, fc::MetaballKernel::Inverse, 2000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(20);
BENCHMARK_CAPTURE(BM_Algorithm1Dense, inverse_2k_with_gradient, fc::MetaballKernel::Inverse, 2000,
                  0.25f, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
// The same at the default voxel (a third of the radius): Algorithm 1's dense grid grows with the
// voxel count, the multilevel field's coarse levels do not.
BENCHMARK_CAPTURE(BM_Surface, inverse_2k_default_voxel, fc::MetaballKernel::Inverse, 2000,
                  kRadius / 3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);
BENCHMARK_CAPTURE(BM_Algorithm1Dense, inverse_2k_with_gradient_default_voxel,
                  fc::MetaballKernel::Inverse, 2000, kRadius / 3, true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_SampledErrorAgainstAlgorithm1, inverse_square_50k, 50000, 0.25f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Surface, inverse_square_26k_voxel_0_5, fc::MetaballKernel::InverseSquare,
                  26000, 0.5f)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

// One surface at a time, one build per repetition, and the median of five repetitions
// reported (the issue's figures are medians; the first build of a process also pays for its
// thread pool and fresh pages).
void spreadRuns(benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true)
        ->UseRealTime();
}
BENCHMARK_CAPTURE(BM_SpreadSurface, spread_inverse_r2, fc::MetaballKernel::Inverse, 2.0f)
    ->Apply(spreadRuns);
BENCHMARK_CAPTURE(BM_SpreadSurface, spread_inverse_square_r2, fc::MetaballKernel::InverseSquare,
                  2.0f)
    ->Apply(spreadRuns);
BENCHMARK_CAPTURE(BM_SpreadOpenVdb, spread_openvdb_r2, 2.0f)->Apply(spreadRuns);
BENCHMARK_CAPTURE(BM_SpreadSampledError, spread_error_inverse_r2, fc::MetaballKernel::Inverse)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_SpreadSampledError, spread_error_inverse_square_r2,
                  fc::MetaballKernel::InverseSquare)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_SpreadPlan, spread_plan_inverse_r2, fc::MetaballKernel::Inverse)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10)
    ->UseRealTime();
BENCHMARK(BM_SpreadRemesh)
    ->Name("spread_remesh_inverse_r2")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SpreadSurface, spread_inverse_r3, fc::MetaballKernel::Inverse, 3.0f)
    ->Apply(spreadRuns);
BENCHMARK_CAPTURE(BM_SpreadSurface, spread_inverse_square_r3, fc::MetaballKernel::InverseSquare,
                  3.0f)
    ->Apply(spreadRuns);
BENCHMARK_CAPTURE(BM_SpreadOpenVdb, spread_openvdb_r3, 3.0f)->Apply(spreadRuns);
// The ratio cases run their own rounds inside one iteration.
void ratioRuns(benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
}
BENCHMARK_CAPTURE(BM_CompactRatio, compact_ratio_50k, 50000, 0.25f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SpreadRatio, spread_ratio_r2, 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SpreadRatio, spread_ratio_r3, 3.0f)->Apply(ratioRuns);
// Issue 40's cases, whole op against OpenVDB: three dense zones from a 525k block, the demo's
// last frame at broken_bonds >= 3, a real LAMMPS run's shear bands, the sparse spread set and
// the compact 50k zone; r/2 and r/3.
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_zones525k_r2, "zones525k", 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_zones525k_r3, "zones525k", 3.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_demo_bb3_r2, "demo_bb3", 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_demo_bb3_r3, "demo_bb3", 3.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_lammps_bands_r2, "lammps_bands", 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_lammps_bands_r3, "lammps_bands", 3.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_sparse_spread_r2, "sparse_spread", 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_sparse_spread_r3, "sparse_spread", 3.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_compact_50k_r2, "compact_50k", 2.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpRatio, op_compact_50k_r3, "compact_50k", 3.0f)->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpSampledError, op_error_demo_bb3_inverse_r3, "demo_bb3", 3.0f,
                  fc::MetaballKernel::Inverse, 199)
    ->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpSampledError, op_error_demo_bb3_inverse_square_r3, "demo_bb3", 3.0f,
                  fc::MetaballKernel::InverseSquare, 199)
    ->Apply(ratioRuns);
// The case nearest the 2x line (r/d^2 at r/2 on the zones): its accuracy, measured.
BENCHMARK_CAPTURE(BM_SurfaceOpSampledError, op_error_zones525k_inverse_square_r2, "zones525k", 2.0f,
                  fc::MetaballKernel::InverseSquare, 23)
    ->Apply(ratioRuns);
BENCHMARK_CAPTURE(BM_SurfaceOpSampledError, op_error_zones525k_inverse_r3, "zones525k", 3.0f,
                  fc::MetaballKernel::Inverse, 199)
    ->Apply(ratioRuns);
BENCHMARK_MAIN();
