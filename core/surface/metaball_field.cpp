// MetaballField: the paper's field (eq. 1: every sphere's kernel, r/d or r/d^2, summed)
// on sparse 8^3 voxel blocks, to within `tolerance` of the iso-value at every stored voxel.
//
// The algorithm (multilevel summation):
//   - Each kernel is split into a near part, exact within a cutoff a0 (level 1), and a smooth
//     remainder. The remainder is carried on ever coarser grids of charges, each level's smooth
//     part interpolated (degree 5) onto the levels below and finally onto the voxels; the top
//     level sums its charges directly.
//   - The cutoffs (kappa = a0 / level-1 spacing, and the coarse levels' kappa) are chosen from
//     an a priori error estimate (errorScale(), calibrated by bench/calibrate_field_error) so the
//     error stays within the budget at the lowest cost; for small sets they are chosen again
//     once the levels are planned.
//   - Block planning: bounds of the field over each candidate block (direct sums for small sets,
//     the sphere tree otherwise) discard blocks that cannot meet the iso range; coarse nodes are
//     kept only where planned blocks need them.
//   - Evaluation: per block, the coarse part interpolated, then the near sums over the spheres
//     within a0 (gathered from a grid of block-sized cells; SIMD, 8 voxels at a time); blocks
//     whose bounds put them on one side of the iso range skip their near sums.
//
// Files (one class, four files; shared parts in detail/metaball_field_common.hpp):
//   metaball_field.cpp         construction, the choice of cutoffs, the error model
//   metaball_field_plan.cpp    bounds over boxes, planning the levels blocks need
//   metaball_field_levels.cpp  prepare(): the levels' values for planned blocks
//   metaball_field_eval.cpp    evaluating blocks, the near field, points
//
// Sections:
//   [SECTION] Error model: constants, weights, budget (metaball_field_common.hpp)
//   [SECTION] Kernels: softened inner parts, power coefficients (metaball_field_common.hpp)
//   [SECTION] Construction and the choice of cutoffs (MetaballField::MetaballField, errorScale):
//   this file [SECTION] Bounds over boxes (MetaballField::bounds): metaball_field_plan.cpp
//   [SECTION] Planning levels (planLevels, levelsEstimate, errorTerm): metaball_field_plan.cpp
//   [SECTION] Preparing the levels (prepare and its steps): metaball_field_levels.cpp
//   [SECTION] Evaluating blocks (evaluateBlock, ...): metaball_field_eval.cpp
//   [SECTION] Near field (nearValues, sumNear) and points: metaball_field_eval.cpp

#include "core/surface/metaball_field.hpp"

#include "core/surface/detail/metaball_field_common.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace faultline::core {

using namespace field_internal;

//-----------------------------------------------------------------------------
// [SECTION] Construction and the choice of cutoffs
//-----------------------------------------------------------------------------

MetaballField::MetaballField(const SphereSet& spheres, const SurfaceParams& params, float voxelSize,
                             const MultilevelTuning& tuning)
    : m_tree(spheres), m_grid(m_tree.spheres(), m_tree.root().box, kBlockDim * voxelSize),
      m_params(params), m_tuning(tuning), m_h(voxelSize) {
    double mean = 0.0;
    for (float r : m_tree.spheres().r)
        mean += r;
    mean /= static_cast<double>(sphereCount());
    m_meanRadius = mean;
    const float minD = kMinDistanceFactor * static_cast<float>(mean);
    m_kernel = InverseKernel{params.kernel == MetaballKernel::Inverse ? 1 : 2, minD * minD};
    if (params.kernel != MetaballKernel::Compact) {
        // The tolerance at the lowest iso; the estimate is already pessimistic (kErrorPerScale
        // is 1.5x the worst error measured, and errors of levels and spheres are added).
        const double budget = errorBudget(params);
        // Among the (kappa, coarse kappa) pairs that meet the budget, the cheapest by a work
        // model: the near field costs about a_0^3 per voxel, each coarse level about
        // (a_1 / ratio_1)^3 per voxel, with the weights measured on bench_surface's fault zone.
        // With none, the most accurate pair.
        using Choice = CutoffChoice;
        std::vector<Choice> candidates;
        m_sparse = isSparse();
        const double nearRadii =
            m_tuning.nearCutoffRadii * (m_sparse ? std::max(1.0, m_tuning.sparseNearFactor) : 1.0);
        for (int kappa = kKappaMin; kappa <= kKappaMax; ++kappa) {
            if (m_tuning.kappa > 0 && kappa != m_tuning.kappa)
                continue;
            // Level 1 at least two voxels apart (else it has more nodes than there are voxels);
            // the near cutoff about nearCutoffRadii radii.
            const double target = nearRadii * mean;
            const int ratio = std::max(
                m_sparse ? std::max(m_tuning.minRatio, m_tuning.sparseMinRatio) : m_tuning.minRatio,
                static_cast<int>(std::lround(target / (kappa * m_h))));
            for (int coarse = std::max(kKappaMin, kappa / 2 + 1); coarse <= kKappaMax; ++coarse) {
                if (m_tuning.coarseKappa > 0 &&
                    coarse != std::max(m_tuning.coarseKappa, kappa / 2 + 1))
                    continue;
                candidates.push_back({kappa, coarse, ratio, 0.0,
                                      5.0 * std::pow(double(kappa * ratio), 3) +
                                          56.0 * std::pow(double(coarse), 3)});
            }
        }
        // Cheapest first: the first whose estimate fits is the choice, and the dearer ones need
        // no estimate (each costs tree walks at up to eight cutoffs).
        std::stable_sort(candidates.begin(), candidates.end(),
                         [](const Choice& a, const Choice& b) { return a.cost < b.cost; });
        std::optional<std::size_t> best;
        auto estimate = [&](Choice& c, double stopAbove) {
            applyChoice(c);
            const std::array<double, 2> weights = errorWeights(c.kappa, c.coarse, m_kernel.p);
            const auto scale = errorScale(&m_densest, nullptr, weights, stopAbove);
            c.error = weights[0] * scale[0] + weights[1] * scale[1];
        };
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            // Over the budget part way through the levels: no need for the rest of them.
            estimate(candidates[i], budget);
            if (candidates[i].error <= budget) {
                best = i;
                break;
            }
        }
        // With none that fits, the most accurate (every estimate in full).
        std::size_t chosen = 0;
        if (best) {
            chosen = *best;
            // The cheaper ones may still fit with fewer levels than this estimate assumes:
            // prepare() tries them again with the levels planned, for a few thousand spheres
            // (each try costs a plan and the weight within its cutoffs, under a millisecond
            // there, but about 15 ms at 50,000 spheres, for no cheaper choice on the bench's sets).
            if (sphereCount() <= kDirectBoundsSpheres)
                m_cheaper.assign(candidates.begin(), candidates.begin() + std::ptrdiff_t(chosen));
        } else {
            for (std::size_t i = 0; i < candidates.size(); ++i) {
                estimate(candidates[i], std::numeric_limits<double>::infinity());
                if (candidates[i].error < candidates[chosen].error)
                    chosen = i;
            }
        }
        applyChoice(candidates[chosen]);
        m_estimatedError = candidates[chosen].error;
        errorScale(&m_densest, &m_errorTerms);
    } else {
        m_a0 = params.compactReach * maxRadius();
    }
}

bool MetaballField::isSparse() const {
    // Touching spheres (HCP) put about 20 radii of weight within 3 radii of a sphere; a sparse
    // selection (the high-strain spheres of fault zones spread over a block) puts a few.
    const auto& s = m_tree.spheres();
    const std::size_t n = s.size(), samples = std::min<std::size_t>(n, 64);
    if (samples == 0)
        return false;
    const double a = 3.0 * m_meanRadius;
    std::vector<double> within(samples);
    tbb::parallel_for(std::size_t{0}, samples, [&](std::size_t q) {
        const std::size_t i = q * n / samples;
        within[q] = weightWithin({s.x[i], s.y[i], s.z[i]}, a) / m_meanRadius;
    });
    std::nth_element(within.begin(), within.begin() + samples / 2, within.end());
    return within[samples / 2] < kSparseNeighbours;
}

void MetaballField::applyChoice(const CutoffChoice& c) {
    m_kappa = c.kappa;
    m_coarseKappa = c.coarse;
    m_ratio1 = c.ratio;
    m_a0 = static_cast<float>(c.kappa) * static_cast<float>(c.ratio) * m_h;
    m_soft0 = SoftenedKernel(m_kernel.p, m_a0, m_tuning.softeningOrder);
}

std::array<double, 2> MetaballField::estimatedErrorParts() const {
    if (m_errorTerms.empty())
        return {0.0, 0.0};
    const double level1 = errorWeights(m_kappa, m_coarseKappa, m_kernel.p)[0] * m_errorTerms[0];
    return {level1, m_estimatedError - level1};
}

double MetaballField::cutoff(int l) const {
    // a_0 = kappa * H_1; a_l = coarseKappa * H_{l+1} with H_{l+1} = 2^l H_1 (2 coarseKappa >
    // kappa).
    if (l == 0)
        return m_a0;
    return double(m_coarseKappa) * double(m_ratio1) * m_h * std::ldexp(1.0, l);
}

std::array<double, 2> MetaballField::errorScale(std::map<double, double>* memo,
                                                std::vector<double>* terms,
                                                const std::array<double, 2>& weights,
                                                double stopAbove) const {
    // The densest weight within each cutoff over cutoff^p: the size of what each level
    // interpolates. [0]: level 1 (spacing a_0 / kappa), [1]: the coarser levels together.
    const auto& s = m_tree.spheres();
    const std::size_t n = s.size();
    const std::size_t samples = std::min<std::size_t>(n, 256);
    const auto& box = centreBox();
    double span2 = 0.0;
    for (int k = 0; k < 3; ++k)
        span2 += double(box.hi[k] - box.lo[k]) * (box.hi[k] - box.lo[k]);
    std::array<double, 2> scale{0.0, 0.0};
    if (terms)
        terms->clear();
    for (int l = 0;; ++l) {
        const double a = cutoff(l);
        const auto known = memo ? memo->find(a) : std::map<double, double>::iterator{};
        double densest = 0.0;
        if (memo && known != memo->end()) {
            densest = known->second;
        } else {
            densest = tbb::parallel_reduce(
                tbb::blocked_range<std::size_t>(0, samples), 0.0,
                [&](const tbb::blocked_range<std::size_t>& range, double most) {
                    for (std::size_t q = range.begin(); q != range.end(); ++q) {
                        const std::size_t i = q * n / samples;
                        most = std::max(most, weightWithin({s.x[i], s.y[i], s.z[i]}, a));
                    }
                    return most;
                },
                [](double x, double y) { return std::max(x, y); });
            if (memo)
                memo->emplace(a, densest);
        }
        double term = densest / (m_kernel.p == 2 ? a * a : a);
        // Few spheres within the near cutoff: little cancellation (see kFewSpheres).
        if (l == 0 && m_kernel.p == 2 && densest > 0.0)
            term *= std::max(1.0, kFewSpheres * m_meanRadius / densest);
        scale[l == 0 ? 0 : 1] += term;
        if (terms)
            terms->push_back(term);
        if (weights[0] * scale[0] + weights[1] * scale[1] > stopAbove)
            break;
        if (a * a > 4.0 * span2)
            break;
    }
    return scale;
}

MetaballField::~MetaballField() = default;

double MetaballField::reach(double iso) const {
    if (m_params.kernel == MetaballKernel::Compact)
        return m_params.compactReach * maxRadius();
    const double ratio = totalWeight() / iso;
    return m_kernel.p == 2 ? std::sqrt(ratio) : ratio;
}

std::size_t MetaballField::coarseNodeCount() const {
    std::size_t n = 0;
    for (const auto& l : m_levels)
        n += l->neededCount();
    return n;
}

} // namespace faultline::core
