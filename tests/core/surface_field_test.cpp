// The multilevel metaball field against the paper's Algorithm 1 (dense all-pairs sum).
#include "core/session/fault_surface_request.hpp"
#include "core/surface/detail/charge_grid.hpp"
#include "core/surface/detail/field_level.hpp"
#include "core/surface/detail/plan_fold.hpp"
#include "core/surface/detail/sphere_grid.hpp"
#include "core/surface/detail/sphere_tree.hpp"
#include "core/surface/fault_surface.hpp"
#include "core/surface/metaball_field.hpp"
#include "core/surface/metaball_reference.hpp"
#include "core/surface/surface_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace fc = faultline::core;

namespace {

struct FieldSpheres {
    std::vector<float> x, y, z, r, rgb;
    fc::SphereSet set() const { return {x, y, z, r, rgb}; }
};

// A slab-shaped "fault zone" of jittered spheres, deterministic.
FieldSpheres slab(int nx, int ny, int nz, unsigned seed) {
    FieldSpheres s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.15f, 0.15f), radius(0.4f, 0.6f);
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k) {
                s.x.push_back(i + jitter(rng));
                s.y.push_back(j + jitter(rng));
                s.z.push_back(0.9f * k + jitter(rng));
                s.r.push_back(radius(rng));
                s.rgb.insert(s.rgb.end(), {i / float(nx), j / float(ny), k / float(nz)});
            }
    return s;
}

struct Check {
    double maxError = 0.0;
    std::size_t voxels = 0;
    std::size_t colorMismatches = 0;
};

// Evaluates every planned block and compares every voxel with Algorithm 1.
Check compareWithReference(const FieldSpheres& s, const fc::SurfaceParams& params, float voxel,
                           float isoMin, float isoMax, const fc::MultilevelTuning& tuning,
                           int* levels = nullptr, int* chargeLevels = nullptr,
                           double* estimate = nullptr, std::array<int, 2>* cutoffs = nullptr) {
    const auto set = s.set();
    fc::MetaballField field(set, params, voxel, tuning);
    const auto plan = fc::planSurface(field, isoMin, isoMax, std::size_t{1} << 30, nullptr);
    field.prepare(plan.blocks, nullptr);
    if (levels)
        *levels = field.levelCount();
    if (chargeLevels)
        *chargeLevels = field.anterpolatedLevels();
    if (estimate)
        *estimate = field.estimatedError();
    if (cutoffs)
        *cutoffs = {field.kappa(), field.coarseKappa()};
    Check check;
    const double clamp = 4.0 * isoMax;
    std::vector<float> density(fc::kBlockVoxels);
    std::vector<fc::Vec3f> color(fc::kBlockVoxels);
    for (const auto& o : plan.blocks) {
        field.evaluateBlock(o, density.data(), color.data());
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j)
                for (int k = 0; k < 8; ++k) {
                    const int off = fc::blockOffset(i, j, k);
                    const auto ref =
                        fc::referenceSample(set, params,
                                            {(o[0] + i) * double(voxel), (o[1] + j) * double(voxel),
                                             (o[2] + k) * double(voxel)});
                    const double err = std::abs(std::min<double>(density[off], clamp) -
                                                std::min(ref.value, clamp));
                    check.maxError = std::max(check.maxError, err);
                    for (int c = 0; c < 3; ++c)
                        if (std::abs(color[off][c] - ref.color[c]) > 1e-5f) {
                            ++check.colorMismatches;
                            break;
                        }
                    ++check.voxels;
                }
    }
    return check;
}

// A spread-out selection as a strain threshold makes it (issue 23): every fourth sphere of a cubic
// packing (spacing 2, radius 1) within 1.5 of three dipping planes that cross a box of
// size[0] x size[1] x size[2], so most of the box is far from any sphere.
// every: keep one sphere in `every` (1: dense zones, every sphere of the packing kept).
FieldSpheres spreadZones(std::array<double, 3> size, unsigned seed, int every = 4) {
    FieldSpheres s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
    const double c = std::cos(60.0 * M_PI / 180.0), d = std::sin(60.0 * M_PI / 180.0);
    const double normals[3][3] = {{d, 0, c}, {-d, 0, c}, {0, d, c}};
    const double points[3][3] = {{size[0] * 0.35, 0, size[2] / 2},
                                 {size[0] * 0.65, 0, size[2] / 2},
                                 {0, size[1] / 2, size[2] / 2}};
    int n = 0;
    for (double x = 1; x < size[0]; x += 2)
        for (double y = 1; y < size[1]; y += 2)
            for (double z = 1; z < size[2]; z += 2)
                for (int f = 0; f < 3; ++f) {
                    const double across = (x - points[f][0]) * normals[f][0] +
                                          (y - points[f][1]) * normals[f][1] +
                                          (z - points[f][2]) * normals[f][2];
                    if (std::abs(across) > 1.5)
                        continue;
                    if (n++ % every == 0) {
                        s.x.push_back(float(x) + jitter(rng));
                        s.y.push_back(float(y) + jitter(rng));
                        s.z.push_back(float(z) + jitter(rng));
                        s.r.push_back(1.0f);
                        s.rgb.insert(s.rgb.end(), {float(f) / 2, 0.5f, float(z / size[2])});
                    }
                    break;
                }
    return s;
}

} // namespace

// Planning folds far spheres into a linear function and a remainder bound (surface_plan.cpp):
// on a spread-out set, where folding does most of the work, no voxel whose exact field lies in
// the iso range may be left out of the planned blocks, for either inverse kernel.
// Issue 40: dense spread-out zones (every sphere of the packing kept, as in a thick fault zone)
// are planned by folds too, and keep the same guarantee.
TEST(MetaballField, FoldedPlanningKeepsEveryBlockTheSpreadOutSurfaceCrosses) {
    for (const int every : {4, 1})
        for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
            const FieldSpheres s = spreadZones({80, 50, 40}, 11, every);
            ASSERT_GT(s.x.size(), 500u);
            const auto set = s.set();
            SCOPED_TRACE(std::string(fc::kernelName(kernel)) + (every == 1 ? " dense" : " sparse"));
            fc::SurfaceParams params;
            params.kernel = kernel;
            params.iso = static_cast<float>(fc::wrappingIso(set, params));
            const float voxel = 0.5f;
            fc::MetaballField field(set, params, voxel);
            EXPECT_EQ(field.sparse(), every != 1);
            const float isoMin = params.iso / params.isoRangeFactor;
            const float isoMax = params.iso * params.isoRangeFactor;
            const auto plan = fc::planSurface(field, isoMin, isoMax, std::size_t{1} << 30, nullptr);
            ASSERT_FALSE(plan.blocks.empty());
            std::vector<fc::Coord3> blocks = plan.blocks;
            std::sort(blocks.begin(), blocks.end());
            // Voxels near random spheres (where the surface is) and anywhere in the box.
            std::mt19937 rng(5);
            std::uniform_int_distribution<std::size_t> pick(0, s.x.size() - 1);
            std::uniform_real_distribution<double> offset(-4.0, 4.0), anywhere(-5.0, 85.0);
            int inRange = 0;
            for (int n = 0; n < 12000; ++n) {
                std::array<double, 3> p;
                if (n % 2 == 0) {
                    const std::size_t i = pick(rng);
                    p = {s.x[i] + offset(rng), s.y[i] + offset(rng), s.z[i] + offset(rng)};
                } else {
                    p = {anywhere(rng), anywhere(rng) * 50 / 80, anywhere(rng) * 40 / 80};
                }
                const std::array<int, 3> v{int(std::floor(p[0] / voxel)),
                                           int(std::floor(p[1] / voxel)),
                                           int(std::floor(p[2] / voxel))};
                const auto ref = fc::referenceSample(
                    set, params, {v[0] * voxel, v[1] * double(voxel), v[2] * voxel});
                if (ref.value < isoMin || ref.value > isoMax)
                    continue;
                ++inRange;
                const fc::Coord3 o{fc::detail::floorDiv(v[0], 8) * 8,
                                   fc::detail::floorDiv(v[1], 8) * 8,
                                   fc::detail::floorDiv(v[2], 8) * 8};
                EXPECT_TRUE(std::binary_search(blocks.begin(), blocks.end(), o))
                    << "voxel " << v[0] << "," << v[1] << "," << v[2] << " value " << ref.value;
            }
            EXPECT_GT(inRange, 50); // the samples did reach the surface
        }
}

// Issue 40: planning a dense set by folds instead of the tree's bounds changes no mesh: the same
// triangles through the same vertices, for both inverse kernels. (Block counts differ a little
// either way here; on the demo's 30k spheres the tree, giving up on cells, kept twice as many.)
TEST(MetaballField, FoldedAndTreePlanningGiveTheSameMeshOnADenseSet) {
    const FieldSpheres s = spreadZones({40, 30, 30}, 3, 1);
    const auto set = s.set();
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
        SCOPED_TRACE(std::string(fc::kernelName(kernel)));
        fc::SurfaceParams params;
        params.kernel = kernel;
        params.voxelSize = 0.4f;
        params.iso = static_cast<float>(fc::wrappingIso(set, params));
        fc::MultilevelTuning tree;
        tree.foldPlanning = false;
        const auto byFolds = fc::buildSurface(set, params, nullptr, fc::MultilevelTuning{});
        const auto byTree = fc::buildSurface(set, params, nullptr, tree);
        ASSERT_GT(byFolds.mesh.triangleCount(), 1000u);
        ASSERT_EQ(byFolds.mesh.triangleCount(), byTree.mesh.triangleCount());
        // As sorted vertex lists (blocks may be meshed in another order).
        auto sorted = [](const fc::SurfaceMesh& m) {
            auto p = m.positions;
            std::sort(p.begin(), p.end());
            return p;
        };
        const auto a = sorted(byFolds.mesh), b = sorted(byTree.mesh);
        ASSERT_EQ(a.size(), b.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, double(std::abs(a[i][k] - b[i][k])));
        EXPECT_LT(worst, 1e-3 * params.voxelSize);
    }
}

// The folds themselves: down random chains of nested boxes (each half its parent, as planning
// cells are), every sampled point's exact field (corners and edges included, where the linear
// part and the remainder are largest) lies within the bounds.
TEST(MetaballField, FoldBoundsHoldEverywhereInNestedBoxes) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const int every : {4, 1}) // sparse and dense zones (issue 40)
        for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
            const FieldSpheres s = spreadZones({80, 50, 40}, 17, every);
            const auto set = s.set();
            SCOPED_TRACE(std::string(fc::kernelName(kernel)) + (every == 1 ? " dense" : " sparse"));
            fc::SurfaceParams params;
            params.kernel = kernel;
            const int power = kernel == fc::MetaballKernel::Inverse ? 1 : 2;
            const float minD2 = 1e-6f; // as the field clamps: far below any distance sampled here
            int folded = 0;
            for (int chain = 0; chain < 12; ++chain) {
                fc::detail::Fold fold;
                fold.x = s.x, fold.y = s.y, fold.z = s.z, fold.r = s.r;
                fc::detail::Box box{{-8, -8, -8}, {88, 88, 88}};
                for (int depth = 0; depth < 6; ++depth) {
                    const auto b = fc::detail::foldBounds(fold, box, power, minD2);
                    for (int n = 0; n < 64; ++n) {
                        std::array<double, 3> p;
                        for (int k = 0; k < 3; ++k) {
                            const double t = n < 8 ? double((n >> k) & 1) : unit(rng);
                            p[k] = box.lo[k] + t * (box.hi[k] - box.lo[k]);
                        }
                        const double v = fc::referenceSample(set, params, p).value;
                        ASSERT_GE(v, b.low) << "depth " << depth;
                        ASSERT_LE(v, b.high) << "depth " << depth;
                    }
                    fold = fc::detail::foldFor(fold, box, power, minD2);
                    folded += fold.x.size() < s.x.size();
                    // A random octant: a child planning cell.
                    for (int k = 0; k < 3; ++k) {
                        const float mid = 0.5f * (box.lo[k] + box.hi[k]);
                        (unit(rng) < 0.5 ? box.hi[k] : box.lo[k]) = mid;
                    }
                }
            }
            EXPECT_GT(folded, 12); // the chains did fold spheres
        }
}

// The grid's near and colour lists hold exactly the spheres the tree gathers (as sets: the
// grid lists them in cell order), for boxes inside, across and outside the spheres' box, small
// and large reaches, with the colours beside their spheres.
TEST(SphereGrid, GathersTheSpheresTheTreeGathers) {
    const FieldSpheres s = spreadZones({80, 50, 40}, 23);
    std::vector<float> rgb(3 * s.x.size());
    for (std::size_t i = 0; i < rgb.size(); ++i)
        rgb[i] = float(i % 97) / 96.0f;
    fc::SphereSet set = s.set();
    set.rgb = rgb;
    const fc::detail::SphereTree tree(set);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> at(-20.0f, 100.0f), side(0.0f, 6.0f), reach(0.0f, 12.0f);
    for (float cell : {0.7f, 4.0f, 1e-3f}) { // the last: capped at kMaxCells
        const fc::detail::SphereGrid grid(tree.spheres(), tree.root().box, cell);
        if (cell < 0.01f) {
            EXPECT_GT(grid.cellSize(), cell);
        }
        for (int n = 0; n < 300; ++n) {
            fc::detail::Box box;
            for (int k = 0; k < 3; ++k) {
                box.lo[k] = at(rng);
                box.hi[k] = box.lo[k] + side(rng);
            }
            const float r = n % 10 == 0 ? 200.0f : reach(rng);
            for (bool withColor : {false, true}) {
                fc::detail::NearList fromTree, fromGrid;
                tree.gather(box, r, fromTree, withColor);
                grid.gather(box, r, fromGrid, withColor);
                auto rows = [&](const fc::detail::NearList& l) {
                    std::vector<std::array<float, 7>> v;
                    for (std::size_t i = 0; i < l.size(); ++i)
                        v.push_back({l.x[i], l.y[i], l.z[i], l.r[i], withColor ? l.red[i] : 0.0f,
                                     withColor ? l.green[i] : 0.0f, withColor ? l.blue[i] : 0.0f});
                    std::sort(v.begin(), v.end());
                    return v;
                };
                ASSERT_EQ(rows(fromTree), rows(fromGrid)) << "cell " << cell << " box " << n;
            }
        }
    }
}

// A sparse set takes a wider near cutoff (fewer level-1 nodes); the field still matches
// Algorithm 1 within the tolerance at every voxel of every planned block.
TEST(MetaballField, SparseSetWiderNearCutoffStillMatchesAlgorithm1) {
    const FieldSpheres s = spreadZones({30, 24, 20}, 3);
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
        SCOPED_TRACE(std::string(fc::kernelName(kernel)));
        fc::SurfaceParams params;
        params.kernel = kernel;
        params.iso = static_cast<float>(fc::wrappingIso(s.set(), params));
        const float voxel = 0.5f;
        fc::MultilevelTuning dense;
        dense.sparseNearFactor = 1.0;
        dense.sparseMinRatio = 0;
        const fc::MetaballField plain(s.set(), params, voxel, dense);
        fc::MetaballField wider(s.set(), params, voxel);
        // r/d^2's budget keeps the same cutoff here; r/d's widens.
        EXPECT_GE(wider.nearCutoff(), plain.nearCutoff());
        if (kernel == fc::MetaballKernel::Inverse) {
            EXPECT_GT(wider.nearCutoff(), plain.nearCutoff());
        }
        const float isoMin = params.iso / params.isoRangeFactor;
        const auto check =
            compareWithReference(s, params, voxel, isoMin, params.iso * params.isoRangeFactor, {});
        EXPECT_GT(check.voxels, 0u);
        EXPECT_LE(check.maxError, params.tolerance * isoMin);
    }
}

TEST(MetaballField, InverseSquareMatchesAlgorithm1WithinTolerance) {
    const FieldSpheres s = slab(10, 10, 3, 1);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::InverseSquare;
    params.colorReach = 0.1f;
    const float iso = 6.0f;
    fc::MultilevelTuning tuning;
    tuning.topLevelPairs = 1e5;
    tuning.topByCost = false; // force several coarse levels on a small set
    int levels = 0;
    const Check c = compareWithReference(s, params, 0.25f, iso / params.isoRangeFactor,
                                         iso * params.isoRangeFactor, tuning, &levels);
    EXPECT_GE(levels, 3);
    EXPECT_GT(c.voxels, 10000u);
    EXPECT_LE(c.maxError, params.tolerance * iso / params.isoRangeFactor) << "voxels " << c.voxels;
    EXPECT_EQ(c.colorMismatches, 0u);
}

// The field picks the near cutoff (kappa) and the coarse levels' cutoffs (coarse kappa) apart, as
// the cheapest pair whose error estimate fits the budget. Where they differ, the field must still
// match Algorithm 1 within the tolerance.
TEST(MetaballField, ACheaperNearCutoffThanTheCoarseLevelsStillMatchesAlgorithm1) {
    const FieldSpheres s = slab(14, 14, 4, 3);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::InverseSquare;
    fc::MultilevelTuning tuning;
    tuning.topLevelPairs = 1e5;
    tuning.topByCost = false;
    bool mixed = false;
    for (float iso : {8.0f, 12.0f, 16.0f}) {
        params.iso = iso;
        fc::MetaballField probe(s.set(), params, 0.25f, tuning);
        if (probe.kappa() == probe.coarseKappa())
            continue;
        mixed = true;
        const Check c = compareWithReference(s, params, 0.25f, iso / params.isoRangeFactor,
                                             iso * params.isoRangeFactor, tuning);
        EXPECT_GT(c.voxels, 10000u);
        EXPECT_LE(c.maxError, params.tolerance * iso / params.isoRangeFactor)
            << "iso " << iso << " kappa " << probe.kappa() << " coarse " << probe.coarseKappa();
    }
    EXPECT_TRUE(mixed) << "no iso here made the near and coarse cutoffs differ";
}

// Coarsening stops where summing every sphere costs less than the windowed levels would: the
// field then has fewer levels and still matches Algorithm 1.
TEST(MetaballField, ATopLevelChosenByCostStillMatchesAlgorithm1) {
    const FieldSpheres s = slab(12, 12, 3, 4);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::InverseSquare;
    const float iso = 7.0f;
    params.iso = iso;
    fc::MultilevelTuning byCost, byCount;
    byCost.topLevelPairs = byCount.topLevelPairs = 1e5;
    byCount.topByCost = false;
    int levelsByCost = 0, levelsByCount = 0;
    const Check c = compareWithReference(s, params, 0.25f, iso / params.isoRangeFactor,
                                         iso * params.isoRangeFactor, byCost, &levelsByCost);
    compareWithReference(s, params, 0.25f, iso / params.isoRangeFactor, iso * params.isoRangeFactor,
                         byCount, &levelsByCount);
    EXPECT_LT(levelsByCost, levelsByCount);
    EXPECT_GT(c.voxels, 10000u);
    EXPECT_LE(c.maxError, params.tolerance * iso / params.isoRangeFactor);
}

// Coarse levels that sum grid charges (multilevel summation's anterpolation) instead of spheres
// add an interpolation error on the spheres' side; the estimate counts it and still bounds the
// error against Algorithm 1.
TEST(MetaballField, GridChargesOnTheCoarseLevelsStillMatchAlgorithm1) {
    const FieldSpheres s = slab(14, 14, 3, 5);
    for (auto kernel : {fc::MetaballKernel::InverseSquare, fc::MetaballKernel::Inverse}) {
        fc::SurfaceParams params;
        params.kernel = kernel;
        params.tolerance = 3e-3f; // room in the budget for charges on every coarse level
        const float iso = kernel == fc::MetaballKernel::Inverse ? 40.0f : 7.0f;
        params.iso = iso;
        fc::MultilevelTuning tuning;
        tuning.topLevelPairs = 1e5;
        tuning.topByCost = false;
        tuning.anterpolateFrom = 2;
        tuning.chargeShare = 1e9; // a small set: charges even where they outnumber the spheres
        int levels = 0, chargeLevels = 0;
        double estimate = 0.0;
        const Check c = compareWithReference(s, params, 0.25f, iso / params.isoRangeFactor,
                                             iso * params.isoRangeFactor, tuning, &levels,
                                             &chargeLevels, &estimate);
        EXPECT_GE(levels, 3);
        EXPECT_GE(chargeLevels, 1);
        EXPECT_GT(c.voxels, 10000u);
        EXPECT_LE(c.maxError, estimate);
        EXPECT_LE(c.maxError, params.tolerance * iso / params.isoRangeFactor)
            << "voxels " << c.voxels;
        EXPECT_EQ(c.colorMismatches, 0u);
    }
}

// At a small near cutoff (here 1.7, about 20 spheres' weight within it, as at the default voxel
// of a third of a radius) the spheres' interpolation errors no longer cancel: the a priori
// estimate, which the field chooses its cutoffs by, must still bound the error. The error was
// 1.4x over it before the estimate counted the spheres within the cutoff.
TEST(MetaballField, TheEstimateBoundsTheErrorWithFewSpheresInTheNearCutoff) {
    const FieldSpheres s = slab(10, 10, 3, 1);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::InverseSquare;
    params.iso = 7.0f;
    fc::MultilevelTuning tuning;
    tuning.kappa = 5;
    tuning.coarseKappa = 8;
    double estimate = 0.0;
    const float voxel = 0.17f;
    fc::MetaballField probe(s.set(), params, voxel, tuning);
    EXPECT_LT(probe.nearCutoff(), 2.0f);
    const Check c = compareWithReference(s, params, voxel, params.iso / params.isoRangeFactor,
                                         params.iso * params.isoRangeFactor, tuning, nullptr,
                                         nullptr, &estimate);
    EXPECT_GT(c.voxels, 10000u);
    EXPECT_LE(c.maxError, estimate);
}

// Anterpolated charges keep the spheres' moments up to the interpolation's degree (5 per axis):
// total weight, centre of weight, second moments. Small grids (a grid per thread) and large ones
// (spread in place by slabs) alike.
TEST(ChargeGrid, ChargesKeepTheSpheresMoments) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    fc::detail::PackedSpheres s;
    fc::detail::Box box;
    for (int i = 0; i < 20000; ++i) {
        const float p[3] = {-30.0f + 60.0f * u(rng), -5.0f + 10.0f * u(rng), 20.0f * u(rng)};
        s.x.push_back(p[0]), s.y.push_back(p[1]), s.z.push_back(p[2]);
        s.r.push_back(0.3f + 0.4f * u(rng));
        for (int k = 0; k < 3; ++k) {
            box.lo[k] = i == 0 ? p[k] : std::min(box.lo[k], p[k]);
            box.hi[k] = i == 0 ? p[k] : std::max(box.hi[k], p[k]);
        }
    }
    for (float spacing : {2.0f, 0.25f}) {
        const auto g = fc::detail::anterpolate(s, box, spacing);
        ASSERT_TRUE(g.has_value());
        const std::size_t nodes = std::size_t(g->dims[0]) * g->dims[1] * g->dims[2];
        EXPECT_EQ(nodes > (std::size_t{1} << 18), spacing < 1.0f) << nodes;
        double want[5] = {}, got[5] = {};
        auto moments = [](double w, double x, double y, double z, double* m) {
            m[0] += w, m[1] += w * x, m[2] += w * y * z, m[3] += w * x * x, m[4] += w * z * z * z;
        };
        for (std::size_t i = 0; i < s.size(); ++i)
            moments(s.r[i], s.x[i], s.y[i], s.z[i], want);
        for (int a = 0; a < g->dims[0]; ++a)
            for (int b = 0; b < g->dims[1]; ++b)
                for (int c = 0; c < g->dims[2]; ++c)
                    moments(g->at(a, b, c), (g->lo[0] + a) * spacing, (g->lo[1] + b) * spacing,
                            (g->lo[2] + c) * spacing, got);
        for (int m = 0; m < 5; ++m)
            EXPECT_NEAR(got[m], want[m],
                        2e-4 * std::max(1.0, std::abs(want[m])) * (m == 4 ? 20.0 : 1.0))
                << "spacing " << spacing << " moment " << m;
        // Spread twice, the same charges (no race between the threads' slabs).
        EXPECT_EQ(fc::detail::anterpolate(s, box, spacing)->q, g->q);
    }
}

// The suggested iso wraps the spheres: every centre is inside, a point four radii above the slab
// is outside (half the slab's width above, for the long-tailed inverse kernel); for each kernel,
// and for a slab four times as large (whose tails add up to a far larger field: no fixed iso
// would do for both).
TEST(MetaballField, WrappingIsoHugsTheSpheres) {
    for (int size : {6, 12})
        for (auto kernel : {fc::MetaballKernel::InverseSquare, fc::MetaballKernel::Inverse,
                            fc::MetaballKernel::Compact}) {
            const FieldSpheres s = slab(size, size, 3, 7);
            fc::SurfaceParams params;
            params.kernel = kernel;
            const double iso = fc::wrappingIso(s.set(), params);
            ASSERT_GT(iso, 0.0);
            for (std::size_t i = 0; i < s.x.size(); ++i)
                EXPECT_GT(fc::referenceSample(s.set(), params, {s.x[i], s.y[i], s.z[i]}).value,
                          iso);
            const double top = 1.8 + 0.15;
            const double above = kernel == fc::MetaballKernel::Inverse ? size / 2.0 : 2.0;
            EXPECT_LT(
                fc::referenceSample(s.set(), params, {size / 2.0, size / 2.0, top + above}).value,
                iso)
                << "size " << size << " kernel " << fc::kernelName(kernel);
        }
}

// The wrapping iso sums the field without its gradient and colour, faster; it is still exactly
// the lower quartile, over 96 spheres, of referenceSample's lowest value 1.5 radii out along
// the axes (the same double: meshes and replays at "iso":"wrap" do not move).
TEST(MetaballField, WrappingIsoIsExactlyTheReferenceSamplesQuartile) {
    const FieldSpheres s = slab(12, 11, 3, 5);
    const auto set = s.set();
    for (auto kernel : {fc::MetaballKernel::InverseSquare, fc::MetaballKernel::Inverse,
                        fc::MetaballKernel::Compact}) {
        fc::SurfaceParams params;
        params.kernel = kernel;
        const std::size_t n = s.x.size(), samples = std::min<std::size_t>(n, 96);
        std::vector<double> lowest;
        for (std::size_t q = 0; q < samples; ++q) {
            const std::size_t i = q * n / samples;
            double low = INFINITY;
            for (int d = 0; d < 6; ++d) {
                std::array<double, 3> p{s.x[i], s.y[i], s.z[i]};
                p[d / 2] += (d % 2 ? -1.5 : 1.5) * s.r[i];
                low = std::min(low, fc::referenceSample(set, params, p).value);
            }
            lowest.push_back(low);
        }
        std::sort(lowest.begin(), lowest.end());
        EXPECT_EQ(fc::wrappingIso(set, params), lowest[samples / 4]) << fc::kernelName(kernel);
    }
}

TEST(MetaballField, InverseMatchesAlgorithm1WithinTolerance) {
    const FieldSpheres s = slab(9, 8, 3, 2);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Inverse;
    const float iso = 40.0f;
    fc::MultilevelTuning tuning;
    tuning.topLevelPairs = 1e5;
    tuning.topByCost = false;
    int levels = 0;
    const Check c = compareWithReference(s, params, 0.2f, iso / params.isoRangeFactor,
                                         iso * params.isoRangeFactor, tuning, &levels);
    EXPECT_GE(levels, 3);
    EXPECT_GT(c.voxels, 10000u);
    EXPECT_LE(c.maxError, params.tolerance * iso / params.isoRangeFactor) << "voxels " << c.voxels;
}

TEST(MetaballField, CompactIsExactWithinItsSupport) {
    const FieldSpheres s = slab(6, 5, 2, 3);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Compact;
    const Check c = compareWithReference(s, params, 0.2f, 0.3f, 0.6f, {});
    EXPECT_GT(c.voxels, 1000u);
    EXPECT_LE(c.maxError, 1e-5);
}

TEST(MetaballField, GradientAtPointsMatchesAnalyticGradient) {
    const FieldSpheres s = slab(8, 8, 2, 4);
    const auto set = s.set();
    fc::SurfaceParams params;
    const float iso = 5.0f;
    fc::MultilevelTuning tuning;
    tuning.topLevelPairs = 1e4;
    fc::MetaballField field(set, params, 0.25f, tuning);
    const auto plan = fc::planSurface(field, iso / params.isoRangeFactor,
                                      iso * params.isoRangeFactor, std::size_t{1} << 30, nullptr);
    field.prepare(plan.blocks, nullptr);
    std::mt19937 rng(5);
    std::vector<fc::Vec3f> points;
    for (int n = 0; n < 200; ++n) {
        const auto& o = plan.blocks[rng() % plan.blocks.size()];
        std::uniform_real_distribution<float> u(0.0f, 7.0f);
        points.push_back(
            {(o[0] + u(rng)) * 0.25f, (o[1] + u(rng)) * 0.25f, (o[2] + u(rng)) * 0.25f});
    }
    std::vector<float> values(points.size());
    std::vector<fc::Vec3f> grads(points.size());
    field.evaluatePoints(points, values.data(), grads.data());
    for (std::size_t n = 0; n < points.size(); ++n) {
        const auto ref =
            fc::referenceSample(set, params, {points[n][0], points[n][1], points[n][2]});
        if (ref.value > 4 * iso)
            continue;
        EXPECT_NEAR(values[n], ref.value, params.tolerance * iso);
        const double norm = std::hypot(ref.gradient[0], ref.gradient[1], ref.gradient[2]);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(grads[n][k], ref.gradient[k], 1e-2 * norm + 1e-3);
    }
}

// The dense baseline the benchmark times, with Algorithm 1 line 8's gradient, against the
// double-precision reference at every voxel, for all three kernels.
TEST(MetaballField, DenseAlgorithm1WithGradientMatchesTheReference) {
    const FieldSpheres s = slab(5, 4, 2, 6);
    const auto set = s.set();
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare,
                        fc::MetaballKernel::Compact}) {
        SCOPED_TRACE(std::string(fc::kernelName(kernel)));
        fc::SurfaceParams params;
        params.kernel = kernel;
        const std::array<int, 3> origin{-4, -3, -2}, dims{9, 7, 5};
        const float h = 0.7f;
        std::vector<std::array<float, 3>> gradient;
        const auto withGradient = fc::algorithm1Dense(set, params, origin, dims, h, &gradient);
        const auto valueOnly = fc::algorithm1Dense(set, params, origin, dims, h);
        ASSERT_EQ(gradient.size(), withGradient.size());
        std::size_t at = 0;
        for (int k = 0; k < dims[2]; ++k)
            for (int j = 0; j < dims[1]; ++j)
                for (int i = 0; i < dims[0]; ++i, ++at) {
                    const auto ref = fc::referenceSample(
                        set, params,
                        {(origin[0] + i) * h, (origin[1] + j) * h, (origin[2] + k) * h});
                    EXPECT_NEAR(withGradient[at], ref.value, 1e-5 * ref.value + 1e-6);
                    EXPECT_EQ(withGradient[at], valueOnly[at]);
                    const double norm =
                        std::hypot(ref.gradient[0], ref.gradient[1], ref.gradient[2]);
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(gradient[at][c], ref.gradient[c], 1e-5 * norm + 1e-6);
                }
    }
}

TEST(MetaballField, PlanLeavesOnlyBlocksThatCannotHoldTheSurface) {
    const FieldSpheres s = slab(6, 6, 2, 6);
    const auto set = s.set();
    fc::SurfaceParams params;
    fc::MetaballField field(set, params, 0.25f);
    const float isoMin = 3.0f, isoMax = 6.0f;
    const auto plan = fc::planSurface(field, isoMin, isoMax, std::size_t{1} << 30, nullptr);
    ASSERT_FALSE(plan.blocks.empty());
    // Any voxel whose exact field lies in [isoMin, isoMax] must be in a planned block.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 9.0);
    for (int n = 0; n < 3000; ++n) {
        const std::array<int, 3> v{int(std::floor(u(rng) / 0.25)), int(std::floor(u(rng) / 0.25)),
                                   int(std::floor((u(rng) - 3.0) / 0.25))};
        const auto ref = fc::referenceSample(set, params, {v[0] * 0.25, v[1] * 0.25, v[2] * 0.25});
        if (ref.value < isoMin || ref.value > isoMax)
            continue;
        const fc::Coord3 o{fc::detail::floorDiv(v[0], 8) * 8, fc::detail::floorDiv(v[1], 8) * 8,
                           fc::detail::floorDiv(v[2], 8) * 8};
        EXPECT_NE(std::find(plan.blocks.begin(), plan.blocks.end(), o), plan.blocks.end());
    }
}

TEST(MetaballField, RefusesAVoxelSizeOverTheMemoryBudget) {
    const FieldSpheres s = slab(20, 20, 2, 8);
    fc::SurfaceParams params;
    fc::MetaballField field(s.set(), params, 0.01f);
    try {
        fc::planSurface(field, 4.0f, 8.0f, std::size_t{64} << 20, nullptr);
        FAIL() << "expected a refusal";
    } catch (const fc::SurfaceRequestError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("budget is 64.0 MiB"), std::string::npos) << what;
        EXPECT_NE(what.find("needs"), std::string::npos) << what;
    }
}

// The constructor chooses the cutoffs by an estimate with coarse levels up to twice the span;
// prepare() may then take cheaper ones that fit with the levels it planned. Where it does, the
// field must still match Algorithm 1 within the tolerance, and within its estimate.
// Issue 23: r/d at iso 1 over a spread-out set is a shell hundreds of units out. It is refused
// before any planning (no level counted), offering the wrapping iso and no absurd voxel size.
TEST(MetaballField, AnIsoFarBelowTheFieldIsRefusedAtOnceWithTheWrappingIso) {
    const FieldSpheres s = spreadZones({80, 50, 40}, 11);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Inverse;
    params.iso = 1.0f;
    fc::MetaballField field(s.set(), params, 0.5f);
    const double wrap = fc::wrappingIso(s.set(), params);
    try {
        fc::planSurface(field, params.iso / params.isoRangeFactor,
                        params.iso * params.isoRangeFactor, std::size_t{64} << 20, nullptr);
        FAIL() << "expected a refusal";
    } catch (const fc::SurfaceRequestError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("needs at least"), std::string::npos) << what;
        EXPECT_NE(what.find("\"iso\":\"wrap\""), std::string::npos) << what;
        EXPECT_NE(what.find("shell about"), std::string::npos) << what;
        // The wrapping iso of a sample of the spheres (in the field's order): about the same.
        const auto at = what.find("spheres, about ");
        ASSERT_NE(at, std::string::npos) << what;
        const double offered = std::stod(what.substr(at + 15));
        EXPECT_NEAR(offered, wrap, 0.1 * wrap) << what;
        EXPECT_EQ(what.find("voxel size of at least"), std::string::npos) << what;
    }
    // At the wrapping iso the same set fits the same budget.
    params.iso = static_cast<float>(wrap);
    fc::MetaballField wrapped(s.set(), params, 0.5f);
    EXPECT_NO_THROW(fc::planSurface(wrapped, params.iso / params.isoRangeFactor,
                                    params.iso * params.isoRangeFactor, std::size_t{64} << 20,
                                    nullptr));
}

TEST(MetaballField, CheaperCutoffsChosenAfterPlanningStillMatchAlgorithm1) {
    const FieldSpheres s = slab(16, 16, 3, 11);
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Inverse;
    params.iso = 60.0f;
    const float voxel = 0.25f;
    const fc::MetaballField probe(s.set(), params, voxel);
    std::array<int, 2> cutoffs{};
    double estimate = 0.0;
    const Check c = compareWithReference(s, params, voxel, params.iso / params.isoRangeFactor,
                                         params.iso * params.isoRangeFactor, {}, nullptr, nullptr,
                                         &estimate, &cutoffs);
    // The constructor chose kappa 4, coarse kappa 5 here; prepare() kappa 3, coarse kappa 4.
    EXPECT_NE(cutoffs, (std::array<int, 2>{probe.kappa(), probe.coarseKappa()}))
        << "prepare() kept kappa " << cutoffs[0] << ", coarse kappa " << cutoffs[1];
    EXPECT_GT(c.voxels, 100000u);
    EXPECT_LE(c.maxError, params.tolerance * params.iso / params.isoRangeFactor);
    EXPECT_LE(c.maxError, estimate);
}

// Blocks that bounds put wholly on one side of the iso range skip their near sums. Where a block
// is skipped, its true values must lie within the bounds and on that side; where it is not, the
// values must be evaluateBlock's, bit for bit.
TEST(MetaballField, OneSidedBlocksSkipOnlyWhatTheirValuesConfirm) {
    const FieldSpheres s = slab(14, 14, 4, 5);
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
        fc::SurfaceParams params;
        params.kernel = kernel;
        params.iso = kernel == fc::MetaballKernel::Inverse ? 40.0f : 8.0f;
        const float voxel = 0.25f;
        fc::MetaballField field(s.set(), params, voxel);
        const float isoMin = params.iso / params.isoRangeFactor;
        const float isoMax = params.iso * params.isoRangeFactor;
        const auto plan = fc::planSurface(field, isoMin, isoMax, std::size_t{1} << 30, nullptr);
        field.prepare(plan.blocks, nullptr);
        std::vector<float> exact(fc::kBlockVoxels), maybe(fc::kBlockVoxels);
        int skipped = 0;
        for (const auto& o : plan.blocks) {
            field.evaluateBlock(o, exact.data(), nullptr);
            const auto [lo, hi] = std::minmax_element(exact.begin(), exact.end());
            fc::FieldBounds bounds;
            const int side =
                field.evaluateBlockUnlessOneSided(o, maybe.data(), isoMin, isoMax, &bounds);
            if (side == 0) {
                EXPECT_EQ(maybe, exact);
                continue;
            }
            ++skipped;
            EXPECT_LE(bounds.low, *lo);
            EXPECT_GE(bounds.high, *hi);
            if (side < 0)
                EXPECT_LT(*hi, isoMin);
            else
                EXPECT_GT(*lo, isoMax);
        }
        EXPECT_GT(skipped, 0) << fc::kernelName(kernel);
    }
}
