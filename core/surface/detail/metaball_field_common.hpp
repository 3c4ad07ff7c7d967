// The parts of MetaballField's implementation that its files share (metaball_field.cpp,
// metaball_field_plan.cpp, metaball_field_levels.cpp, metaball_field_eval.cpp): the error
// model's constants, block boxes, the bound kernel and the softened kernels. Include only from
// those files.
#pragma once

#include "core/surface/detail/charge_grid.hpp"
#include "core/surface/detail/field_level.hpp"
#include "core/surface/metaball_field.hpp"
#include "core/util/simd8.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace faultline::core::field_internal {

using detail::Box;
using detail::Brick;
using detail::ChargeGrid;
using detail::FieldLevel;
using detail::floorDiv;
using detail::NearList;
using detail::packKey;
using detail::WindowList;
namespace simd8 = detail::simd8;

//-----------------------------------------------------------------------------
// [SECTION] Error model: constants, weights, budget
//-----------------------------------------------------------------------------

// Interpolation error of the smooth remainders per unit of near-field scale (see errorScale()),
// for kappa = cutoff / coarse spacing = 3 .. 8, with degree-5 interpolation and C^4 softening.
// With the corrections below, the estimate made from them is at least 1.34x the largest error
// bench/calibrate_field_error measures (every voxel of jittered slabs and an HCP zone, p = 1, 2,
// every kappa and coarse kappa, voxels of 0.25 to 0.6 radii); tests/core/surface_field_test.cpp
// checks fields against Algorithm 1 too.
constexpr double kErrorPerScale[] = {0, 0, 0, 8.4e-3, 2.1e-3, 6e-4, 3e-4, 1.5e-4, 8e-5};
constexpr int kKappaMin = 3, kKappaMax = 8;
// Up to this many spheres, field bounds over a box and the weight within a ball sum every sphere
// (8 at a time) instead of walking the tree: cheaper, and the bounds are tighter (fewer blocks
// to evaluate).
constexpr std::size_t kDirectBoundsSpheres = 4096;
// The coarse levels' part of the estimate, scaled by this for r/d ([0]) and r/d^2 ([1]). Against
// sets of about 2,000 spheres, whose far field is large (bench/calibrate_field_error coarse),
// the largest error measured was 0.40 of the unscaled part with r/d and 0.65 with r/d^2: the
// scale keeps the estimate at least 1.5x over both.
constexpr double kCoarseErrorShare[2] = {0.6, 1.0};
// The table holds for r/d^2. With r/d the largest error measured (bench/calibrate_field_error)
// is at most 0.48 of that estimate over every kappa and cutoff: this share keeps 1.5x over it.
constexpr double kInverseErrorShare = 0.72;
// The table was measured where many spheres lie within the near cutoff, whose interpolation
// errors partly cancel. With r/d^2 and fewer than this many spheres' weight within it (a small
// cutoff, as at the default voxel of a third of a radius), the largest error measured grew to 1.8x
// the estimate; level 1's term is scaled up by kFewSpheres / n there, which brings every
// measured error back under the estimate (at most 0.74 of it).
constexpr double kFewSpheres = 64.0;
// Spheres (weight in mean radii, the sphere itself included) within 3 mean radii of the median
// sphere below which a set counts as sparse (touching spheres have about 20).
constexpr double kSparseNeighbours = 8.0;

// Error per unit of errorScale() term: [0] for level 1's (at kappa), [1] for each coarser
// level's (at the coarse kappa). The a priori estimate is weights[0] * term_0 + weights[1] *
// (sum of the coarse terms).
inline std::array<double, 2> errorWeights(int kappa, int coarseKappa, int power) {
    const double share = power == 1 ? kInverseErrorShare : 1.0;
    return {share * kErrorPerScale[kappa],
            share * kCoarseErrorShare[power - 1] * kErrorPerScale[coarseKappa]};
}

// The largest error the field may make: the tolerance at the lowest supported iso.
inline double errorBudget(const SurfaceParams& params) {
    return params.tolerance * params.iso / params.isoRangeFactor;
}

inline Box voxelBox(const Coord3& lo, const Coord3& hi, float h) {
    Box b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = lo[k] * h;
        b.hi[k] = hi[k] * h;
    }
    return b;
}

// The voxel centres of the block at origin o.
inline Box blockBox(const Coord3& o, float h) {
    return voxelBox(o, {o[0] + kBlockDim - 1, o[1] + kBlockDim - 1, o[2] + kBlockDim - 1}, h);
}

// Kernel value bound for one sphere (or a node of spheres) at squared distance d2.
struct BoundKernel {
    MetaballKernel kernel;
    InverseKernel inverse;
    float compactReach;
    float value(float d2, float radius) const {
        if (kernel != MetaballKernel::Compact)
            return inverse.value(d2);
        const float big = compactReach * radius;
        return compactValue(d2, 1.0f / (big * big));
    }
};

// Hot loops: bodies templated on the kernel power (no branch inside the loops), instantiated in
// FAULTLINE_HOT functions (simd8.hpp).

//-----------------------------------------------------------------------------
// [SECTION] Kernels: softened inner parts, power coefficients
//-----------------------------------------------------------------------------

template <int P> inline float inversePower(float d2, float minD2) {
    d2 = d2 < minD2 ? minD2 : d2;
    if constexpr (P == 2)
        return 1.0f / d2;
    else
        return 1.0f / std::sqrt(d2);
}

// Softened kernel's polynomial part with a multiplication instead of a division.
inline float softInner(const SoftenedKernel& k, float invA2, float d2) {
    const float t = d2 * invA2 - 1.0f;
    return k.scale *
           (k.coef[0] + t * (k.coef[1] + t * (k.coef[2] + t * (k.coef[3] + t * k.coef[4]))));
}

// Sum over a sphere list of w (gamma_below - gamma_own) within own's cutoff (a coarse level's
// window), or of w gamma_below over all of them (top level).
// A softened kernel's polynomial as coefficients of powers of d^2 (no t = d^2 / a^2 - 1 to form
// per pair): C_k = scale / a^2k * sum_j coef_j binomial(j, k) (-1)^(j-k).
inline void powerCoefficients(const SoftenedKernel& kernel, simd8::v8f out[5]) {
    for (int k = 0; k < 5; ++k) {
        double c = 0.0, binomial = 1.0; // binomial(j, k) for j = k first
        for (int j = k; j < 5; ++j) {
            c += kernel.coef[j] * binomial * ((j - k) % 2 ? -1.0 : 1.0);
            binomial = binomial * (j + 1) / (j + 1 - k);
        }
        out[k] = simd8::splat(
            static_cast<float>(double(kernel.scale) * c / std::pow(double(kernel.a2), k)));
    }
}

// Built once per level: the coefficients cost ten pow() calls.
struct WindowKernels {
    simd8::v8f belowA2, ownA2, minD2, one;
    simd8::v8f below[5], own[5]; // coefficients of d^2^k
    WindowKernels(const SoftenedKernel& b, const SoftenedKernel& o, float minD2In) {
        using simd8::splat;
        belowA2 = splat(b.a2), ownA2 = splat(o.a2);
        minD2 = splat(minD2In), one = splat(1.0f);
        powerCoefficients(b, below);
        powerCoefficients(o, own);
    }
};

} // namespace faultline::core::field_internal
