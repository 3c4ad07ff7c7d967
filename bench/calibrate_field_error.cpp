// Checks the field's a priori error estimate (kErrorPerScale and its corrections in
// core/surface/metaball_field.cpp) against Algorithm 1: for each kernel power, near cutoff /
// level-1 spacing (kappa 3 .. 8) and coarse kappa, the largest |multilevel - Algorithm 1| over
// every kept voxel as a fraction of the estimate, over an HCP fault zone and two jittered slabs
// at six voxel sizes from a quarter to 0.6 of a radius (so near cutoffs with few and with many
// spheres within them). The estimate holds where every fraction is under 1; the field chooses
// its cutoffs by it, so it must hold with room. Also level 1's error per unit of its term.
// Then the coarse levels' share against larger sets (coarseLevels()).
// Run: build/bench/calibrate_field_error [near|coarse]  (about 1.5 + 2 minutes on two cores)
#include "bench/fault_zone.hpp"
#include "core/surface/metaball_field.hpp"
#include "core/surface/metaball_reference.hpp"
#include "core/surface/surface_plan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace fb = faultline::bench;
namespace fc = faultline::core;

namespace {

struct Case {
    const char* name;
    fb::FaultZone spheres;
    std::array<double, 3> outside; // a point one unit outside the set: the iso-value there
};

// A slab of jittered spheres (radius 0.4 .. 0.6) in x, y, 0.9 apart in z.
Case slab(int nx, int ny, int nz, unsigned seed) {
    Case c{"slab", {}, {nx / 2.0, ny / 2.0, 0.9 * (nz - 1) + 1.0}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.15f, 0.15f), radius(0.4f, 0.6f);
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k) {
                c.spheres.x.push_back(i + jitter(rng));
                c.spheres.y.push_back(j + jitter(rng));
                c.spheres.z.push_back(0.9f * k + jitter(rng));
                c.spheres.radius.push_back(radius(rng));
            }
    return c;
}

// Spheres of radius 0.5 on a cubic lattice of spacing 1, without jitter: every sphere sits at
// the same place relative to a coarse grid whose spacing divides 1, so their interpolation
// errors add up instead of partly cancelling.
Case lattice(int nx, int ny, int nz) {
    Case c{"lattice", {}, {nx / 2.0, ny / 2.0, nz - 1.0 + 1.0}};
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k) {
                c.spheres.x.push_back(float(i));
                c.spheres.y.push_back(float(j));
                c.spheres.z.push_back(float(k));
                c.spheres.radius.push_back(0.5f);
            }
    return c;
}

Case zone(std::size_t count) {
    const double dip = 60.0 * 3.14159265358979 / 180.0, d = 4.0 / 2 + 1.0;
    return {"hcp zone",
            fb::hcpFaultZone(count, 0.5f, 4.0f),
            {0.3, d * std::sin(dip), d * std::cos(dip)}};
}

struct Measured {
    double error = 0.0, estimate = 0.0, term0 = 0.0, a0 = 0.0, coarse = 0.0;
};

// Largest error over the kept voxels, the field's estimate of it, level 1's error term.
Measured measure(const Case& c, fc::MetaballKernel kernel, int kappa, int coarseKappa,
                 float voxel) {
    const auto set = c.spheres.set();
    fc::SurfaceParams p;
    p.kernel = kernel;
    p.iso = static_cast<float>(fc::referenceSample(set, p, c.outside).value);
    fc::MultilevelTuning tuning;
    tuning.kappa = kappa;
    tuning.coarseKappa = coarseKappa;
    fc::MetaballField field(set, p, voxel, tuning);
    const float isoMin = p.iso / p.isoRangeFactor, isoMax = p.iso * p.isoRangeFactor;
    const auto plan = fc::planSurface(field, isoMin, isoMax, p.memoryBudgetBytes, nullptr);
    field.prepare(plan.blocks, nullptr);
    std::vector<double> terms;
    field.errorScale(nullptr, &terms);
    const double clamp = 4.0 * isoMax;
    double worst = 0.0;
    float density[fc::kBlockVoxels];
    for (const auto& o : plan.blocks) {
        field.evaluateBlock(o, density, nullptr);
        const auto dense = fc::algorithm1Dense(set, p, o, {8, 8, 8}, voxel);
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j)
                for (int k = 0; k < 8; ++k)
                    worst = std::max(
                        worst, std::abs(std::min<double>(density[fc::blockOffset(i, j, k)], clamp) -
                                        std::min<double>(dense[(k * 8 + j) * 8 + i], clamp)));
    }
    return {worst, field.estimatedError(), terms[0], field.nearCutoff(),
            field.estimatedErrorParts()[1]};
}

} // namespace

// The coarse levels' share of the estimate (kCoarseErrorShare) against sets of about 2,000
// spheres, whose far field is large: level 1's error kept small (kappa 5 .. 8) so that what is
// measured is mostly the coarse levels'. Prints the largest error over the coarse part.
void coarseLevels() {
    std::vector<Case> cases{zone(2000), slab(24, 24, 4, 3), slab(12, 12, 14, 5),
                            lattice(13, 13, 12)};
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
        std::printf("%s, coarse levels\n", std::string(fc::kernelName(kernel)).c_str());
        double overall = 0.0, overallTotal = 0.0;
        for (const auto& [kappa, coarse] : {std::pair{5, 3}, {6, 4}, {8, 5}, {8, 8}}) {
            double worst = 0.0, worstTotal = 0.0;
            for (const auto& c : cases)
                for (float voxel : {0.17f, 0.25f}) {
                    const Measured m = measure(c, kernel, kappa, coarse, voxel);
                    worst = std::max(worst, m.error / m.coarse);
                    worstTotal = std::max(worstTotal, m.error / m.estimate);
                    std::printf("    %s voxel %.2f: error %.3g, estimate %.3g (coarse %.3g)\n",
                                c.name, voxel, m.error, m.estimate, m.coarse);
                }
            overall = std::max(overall, worst);
            overallTotal = std::max(overallTotal, worstTotal);
            std::printf("  kappa %d coarse %d: largest error / coarse part %.3f, / estimate %.3f\n",
                        kappa, coarse, worst, worstTotal);
            std::fflush(stdout);
        }
        std::printf("  largest error / coarse part: %.3f, / estimate: %.3f\n", overall,
                    overallTotal);
    }
}

int main(int argc, char** argv) {
    const std::string only = argc > 1 ? argv[1] : "";
    if (only != "near")
        coarseLevels();
    if (only == "coarse")
        return 0;
    std::vector<Case> cases{zone(600), slab(10, 10, 3, 1), slab(14, 8, 4, 7)};
    for (auto kernel : {fc::MetaballKernel::Inverse, fc::MetaballKernel::InverseSquare}) {
        std::printf("%s\n", std::string(fc::kernelName(kernel)).c_str());
        double overall = 0.0;
        for (int kappa = 3; kappa <= 8; ++kappa)
            for (int coarse : {std::max(3, kappa / 2 + 1), 5, 8}) {
                double worst = 0.0, perScale = 0.0;
                for (const auto& c : cases)
                    for (float voxel : {0.125f, 0.15f, 0.17f, 0.2f, 0.25f, 0.3f}) {
                        const Measured m = measure(c, kernel, kappa, coarse, voxel);
                        worst = std::max(worst, m.error / m.estimate);
                        perScale = std::max(perScale, m.error / m.term0);
                    }
                overall = std::max(overall, worst);
                std::printf(
                    "  kappa %d coarse %d: largest error / estimate %.3f, error / term0 %.3g\n",
                    kappa, coarse, worst, perScale);
                std::fflush(stdout);
            }
        std::printf("  largest error / estimate: %.3f\n", overall);
    }
}
