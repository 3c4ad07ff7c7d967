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
//   - Evaluation: per block, the coarse part interpolated, then the near sums (SIMD, 8 spheres
//     at a time); blocks whose bounds put them on one side of the iso range skip their near sums.
//
// Index of this file:
//   [SECTION] Error model: constants, weights, budget
//   [SECTION] Kernels: softened inner parts, power coefficients
//   [SECTION] Construction and the choice of cutoffs (MetaballField::MetaballField, errorScale)
//   [SECTION] Bounds over boxes (MetaballField::bounds)
//   [SECTION] Planning levels (planLevels, levelsEstimate, errorTerm)
//   [SECTION] Preparing the levels for planned blocks (prepare)
//   [SECTION] Evaluating blocks (evaluateColor, evaluateBlock, evaluateBlockUnlessOneSided)
//   [SECTION] Near field (gatherNear, nearValues, sumNear) and points (evaluatePoints)

#include "core/surface/metaball_field.hpp"

#include "core/surface/detail/charge_grid.hpp"
#include "core/surface/detail/field_level.hpp"
#include "core/surface/detail/simd8.hpp"

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

using detail::Box;
using detail::Brick;
using detail::ChargeGrid;
using detail::FieldLevel;
using detail::floorDiv;
using detail::NearList;
using detail::packKey;
using detail::WindowList;
namespace simd8 = detail::simd8;

namespace {

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
std::array<double, 2> errorWeights(int kappa, int coarseKappa, int power) {
    const double share = power == 1 ? kInverseErrorShare : 1.0;
    return {share * kErrorPerScale[kappa],
            share * kCoarseErrorShare[power - 1] * kErrorPerScale[coarseKappa]};
}

// The largest error the field may make: the tolerance at the lowest supported iso.
double errorBudget(const SurfaceParams &params) {
    return params.tolerance * params.iso / params.isoRangeFactor;
}

Box voxelBox(const Coord3 &lo, const Coord3 &hi, float h) {
    Box b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = lo[k] * h;
        b.hi[k] = hi[k] * h;
    }
    return b;
}

// The voxel centres of the block at origin o.
Box blockBox(const Coord3 &o, float h) {
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
// functions compiled for x86-64-v3 too (AVX2 with FMA: "avx2" alone leaves every a * b + c as
// two instructions) and picked at run time by CPU feature.
// clang (the sanitizer build) does not keep the 8-wide helpers' vectors in one ABI across the
// clones and computes garbage: it builds the baseline only (speed does not matter there).
#if defined(__clang__)
#define FAULTLINE_HOT
#else
#define FAULTLINE_HOT __attribute__((target_clones("arch=x86-64-v3", "default")))
#endif

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
inline float softInner(const SoftenedKernel &k, float invA2, float d2) {
    const float t = d2 * invA2 - 1.0f;
    return k.scale *
           (k.coef[0] + t * (k.coef[1] + t * (k.coef[2] + t * (k.coef[3] + t * k.coef[4]))));
}

// Sum over a sphere list of w (gamma_below - gamma_own) within own's cutoff (a coarse level's
// window), or of w gamma_below over all of them (top level).
// A softened kernel's polynomial as coefficients of powers of d^2 (no t = d^2 / a^2 - 1 to form
// per pair): C_k = scale / a^2k * sum_j coef_j binomial(j, k) (-1)^(j-k).
inline void powerCoefficients(const SoftenedKernel &kernel, simd8::v8f out[5]) {
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
    WindowKernels(const SoftenedKernel &b, const SoftenedKernel &o, float minD2In) {
        using simd8::splat;
        belowA2 = splat(b.a2), ownA2 = splat(o.a2);
        minD2 = splat(minD2In), one = splat(1.0f);
        powerCoefficients(b, below);
        powerCoefficients(o, own);
    }
};

template <int P, bool Top>
[[gnu::always_inline]] inline simd8::v8f windowTerm(const WindowKernels &k, simd8::v8f x,
                                                      simd8::v8f y, simd8::v8f z, simd8::v8f px,
                                                      simd8::v8f py, simd8::v8f pz,
                                                      simd8::v8f w) {
    using simd8::v8f;
    const v8f dx = x - px, dy = y - py, dz = z - pz;
    const v8f d2 = dx * dx + dy * dy + dz * dz;
    const v8f inner =
        k.below[0] + d2 * (k.below[1] + d2 * (k.below[2] + d2 * (k.below[3] + d2 * k.below[4])));
    const v8f clamped = simd8::max(d2, k.minD2);
    v8f outer;
    if constexpr (P == 2)
        outer = k.one / clamped;
    else
        outer = simd8::inverseSqrt(clamped);
    v8f v = d2 < k.belowA2 ? inner : outer;
    if constexpr (!Top) {
        v -= k.own[0] + d2 * (k.own[1] + d2 * (k.own[2] + d2 * (k.own[3] + d2 * k.own[4])));
        v = d2 < k.ownA2 ? v : v8f{};
    }
    return w * v;
}

template <int P, bool Top>
[[gnu::always_inline]] inline float windowSumBody(float x, float y, float z, const float *px,
                                                  const float *py, const float *pz,
                                                  const float *pw, std::size_t count,
                                                  const WindowKernels &k) {
    using simd8::load;
    using simd8::v8f;
    const v8f vx = simd8::splat(x), vy = simd8::splat(y), vz = simd8::splat(z);
    v8f acc0{}, acc1{};
    std::size_t q = 0;
    for (; q + 16 <= count; q += 16) {
        acc0 += windowTerm<P, Top>(k, vx, vy, vz, load(px + q), load(py + q), load(pz + q),
                                   load(pw + q));
        acc1 += windowTerm<P, Top>(k, vx, vy, vz, load(px + q + 8), load(py + q + 8),
                                   load(pz + q + 8), load(pw + q + 8));
    }
    for (; q + 8 <= count; q += 8)
        acc0 += windowTerm<P, Top>(k, vx, vy, vz, load(px + q), load(py + q), load(pz + q),
                                   load(pw + q));
    if (q < count) {
        // Padding lanes have weight 0 (and a clamped, finite kernel).
        const std::size_t n = count - q;
        acc1 += windowTerm<P, Top>(k, vx, vy, vz, simd8::loadPartial(px + q, n),
                                   simd8::loadPartial(py + q, n), simd8::loadPartial(pz + q, n),
                                   simd8::loadPartial(pw + q, n));
    }
    return simd8::sum(acc0 + acc1);
}

FAULTLINE_HOT float windowSum1(float x, float y, float z, const float *px, const float *py,
                               const float *pz, const float *pw, std::size_t count,
                               const WindowKernels &kernels, bool top) {
    return top ? windowSumBody<1, true>(x, y, z, px, py, pz, pw, count, kernels)
               : windowSumBody<1, false>(x, y, z, px, py, pz, pw, count, kernels);
}
FAULTLINE_HOT float windowSum2(float x, float y, float z, const float *px, const float *py,
                               const float *pz, const float *pw, std::size_t count,
                               const WindowKernels &kernels, bool top) {
    return top ? windowSumBody<2, true>(x, y, z, px, py, pz, pw, count, kernels)
               : windowSumBody<2, false>(x, y, z, px, py, pz, pw, count, kernels);
}

// Bounds of f over a box from every sphere on its own (no tree): the tightest bounds of their
// kind, and for a few thousand spheres cheaper than opening tree nodes one at a time.
// P: kernel power, 0 for the compact kernel. Sums lo (f at each sphere's farthest point of the
// box) and hi (at its nearest).
template <int P>
[[gnu::always_inline]] inline simd8::v8f boundKernel(simd8::v8f d2, simd8::v8f r, simd8::v8f minD2,
                                                     simd8::v8f invReach2) {
    using simd8::v8f;
    if constexpr (P == 0) {
        const v8f t = simd8::splat(1.0f) - d2 * (invReach2 / (r * r));
        return t > v8f{} ? r * (t * t * t) : v8f{};
    } else if constexpr (P == 2) {
        return r / simd8::max(d2, minD2);
    } else {
        return r * simd8::inverseSqrt(simd8::max(d2, minD2));
    }
}

// Adds one axis's share of the squared distances from centres c to the nearest and farthest
// points of [lo, hi].
[[gnu::always_inline]] inline void boundAxis(simd8::v8f c, simd8::v8f lo, simd8::v8f hi,
                                             simd8::v8f& near2, simd8::v8f& far2) {
    using simd8::max;
    const simd8::v8f gap = max(max(lo - c, c - hi), simd8::v8f{});
    const simd8::v8f span = max(c - lo, hi - c);
    near2 += gap * gap;
    far2 += span * span;
}

template <int P>
[[gnu::always_inline]] inline void directBoundsBody(const float* px, const float* py,
                                                    const float* pz, const float* pr,
                                                    std::size_t count, const Box& box, float minD2,
                                                    float invReach2, double& low, double& high) {
    using simd8::splat;
    using simd8::v8f;
    const v8f lox = splat(box.lo[0]), loy = splat(box.lo[1]), loz = splat(box.lo[2]);
    const v8f hix = splat(box.hi[0]), hiy = splat(box.hi[1]), hiz = splat(box.hi[2]);
    const v8f vmin = splat(minD2), vinv = splat(invReach2);
    v8f lo{}, hi{};
    for (std::size_t q = 0; q < count; q += 8) {
        // Weightless lanes past the end add nothing.
        const std::size_t n = count - q;
        const v8f x = simd8::loadUpTo(px + q, n);
        const v8f y = simd8::loadUpTo(py + q, n);
        const v8f z = simd8::loadUpTo(pz + q, n);
        const v8f r = simd8::loadUpTo(pr + q, n);
        v8f near2{}, far2{};
        boundAxis(x, lox, hix, near2, far2);
        boundAxis(y, loy, hiy, near2, far2);
        boundAxis(z, loz, hiz, near2, far2);
        lo += boundKernel<P>(far2, r, vmin, vinv);
        hi += boundKernel<P>(near2, r, vmin, vinv);
    }
    for (int l = 0; l < 8; ++l) {
        low += lo[l];
        high += hi[l];
    }
}

FAULTLINE_HOT void directBounds0(const float* px, const float* py, const float* pz, const float* pr,
                                 std::size_t count, const Box& box, float minD2, float invReach2,
                                 double& low, double& high) {
    directBoundsBody<0>(px, py, pz, pr, count, box, minD2, invReach2, low, high);
}
FAULTLINE_HOT void directBounds1(const float* px, const float* py, const float* pz, const float* pr,
                                 std::size_t count, const Box& box, float minD2, float invReach2,
                                 double& low, double& high) {
    directBoundsBody<1>(px, py, pz, pr, count, box, minD2, invReach2, low, high);
}
FAULTLINE_HOT void directBounds2(const float* px, const float* py, const float* pz, const float* pr,
                                 std::size_t count, const Box& box, float minD2, float invReach2,
                                 double& low, double& high) {
    directBoundsBody<2>(px, py, pz, pr, count, box, minD2, invReach2, low, high);
}

// Sum of the weights of the spheres whose centres lie within sqrt(a2) of p, 8 at a time.
FAULTLINE_HOT double directWeightWithin(const float* px, const float* py, const float* pz,
                                        const float* pr, std::size_t count, const Vec3f& p,
                                        float a2) {
    using simd8::splat;
    using simd8::v8f;
    const v8f x = splat(p[0]), y = splat(p[1]), z = splat(p[2]), va2 = splat(a2);
    v8f sum{};
    for (std::size_t q = 0; q < count; q += 8) {
        const std::size_t n = count - q;
        const v8f dx = simd8::loadUpTo(px + q, n) - x;
        const v8f dy = simd8::loadUpTo(py + q, n) - y;
        const v8f dz = simd8::loadUpTo(pz + q, n) - z;
        const v8f r = simd8::loadUpTo(pr + q, n);
        sum += dx * dx + dy * dy + dz * dz < va2 ? r : v8f{};
    }
    double total = 0.0;
    for (int l = 0; l < 8; ++l)
        total += sum[l];
    return total;
}

// Exact near field at one voxel: k - gamma_a0 within a0, or the compact kernel (P = 0), over a
// list padded to whole vectors with weightless entries far away.
template <int P>
[[gnu::always_inline]] inline float nearValueBody(float x, float y, float z, const NearList &list,
                                                  float invC2, float a2, float minD2,
                                                  const SoftenedKernel &soft) {
    using simd8::load;
    using simd8::splat;
    using simd8::v8f;
    const v8f vx = splat(x), vy = splat(y), vz = splat(z), one = splat(1.0f);
    const v8f va2 = splat(a2), vmin = splat(minD2), vinvC2 = splat(invC2),
              vinvSoft = splat(1.0f / soft.a2);
    v8f c[5];
    for (int k = 0; k < 5; ++k)
        c[k] = splat(soft.scale * soft.coef[k]);
    auto term = [&](std::size_t q) {
        const v8f dx = vx - load(list.x.data() + q), dy = vy - load(list.y.data() + q),
                  dz = vz - load(list.z.data() + q);
        const v8f r = load(list.r.data() + q);
        const v8f d2 = dx * dx + dy * dy + dz * dz;
        if constexpr (P == 0) {
            const v8f t = one - d2 * (vinvC2 / (r * r));
            return t > v8f{} ? r * (t * t * t) : v8f{};
        } else {
            const v8f clamped = simd8::max(d2, vmin);
            v8f k;
            if constexpr (P == 2)
                k = one / clamped;
            else
                k = simd8::inverseSqrt(clamped);
            const v8f t = d2 * vinvSoft - one;
            const v8f v = k - (c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * c[4]))));
            return d2 < va2 ? r * v : v8f{};
        }
    };
    const std::size_t count = list.size();
    v8f acc0{}, acc1{};
    std::size_t q = 0;
    for (; q + 16 <= count; q += 16) {
        acc0 += term(q);
        acc1 += term(q + 8);
    }
    for (; q < count; q += 8)
        acc0 += term(q);
    return simd8::sum(acc0 + acc1);
}

FAULTLINE_HOT float nearValue0(float x, float y, float z, const NearList &list, float invC2,
                               float a2, float minD2, const SoftenedKernel &soft) {
    return nearValueBody<0>(x, y, z, list, invC2, a2, minD2, soft);
}
FAULTLINE_HOT float nearValue1(float x, float y, float z, const NearList &list, float invC2,
                               float a2, float minD2, const SoftenedKernel &soft) {
    return nearValueBody<1>(x, y, z, list, invC2, a2, minD2, soft);
}
FAULTLINE_HOT float nearValue2(float x, float y, float z, const NearList &list, float invC2,
                               float a2, float minD2, const SoftenedKernel &soft) {
    return nearValueBody<2>(x, y, z, list, invC2, a2, minD2, soft);
}

// Figure 4 colour along a row of 8 voxels (z indices k0 .. k0 + 7): per voxel, the sum of the colours of
// the spheres whose radius + reachAdd holds it, and their number.
FAULTLINE_HOT void colorRow(float x, float y, int k0, float h, const NearList &list,
                            float reachAdd, float red[8], float green[8], float blue[8],
                            float count[8]) {
    using simd8::splat;
    using simd8::v8f;
    v8f z;
    for (int l = 0; l < 8; ++l)
        z[l] = static_cast<float>(k0 + l) * h;
    v8f cr{}, cg{}, cb{}, n{};
    const v8f zero{}, one = splat(1.0f);
    for (std::size_t q = 0; q < list.size(); ++q) {
        const float dx = x - list.x[q], dy = y - list.y[q];
        const float reach = list.r[q] + reachAdd;
        const float dxy2 = dx * dx + dy * dy, reach2 = reach * reach;
        if (dxy2 >= reach2)
            continue; // the sphere misses the whole row
        const v8f dz = z - splat(list.z[q]);
        const auto in = splat(dxy2) + dz * dz < splat(reach2);
        cr += in ? splat(list.red[q]) : zero;
        cg += in ? splat(list.green[q]) : zero;
        cb += in ? splat(list.blue[q]) : zero;
        n += in ? one : zero;
    }
    simd8::store(red, cr), simd8::store(green, cg), simd8::store(blue, cb);
    simd8::store(count, n);
}

// Pads a near list to whole vectors with weightless spheres far from everything.
void padToVectors(NearList &list) {
    while (list.x.size() % 8 != 0) {
        list.x.push_back(1e18f), list.y.push_back(1e18f), list.z.push_back(1e18f);
        list.r.push_back(0.0f);
    }
}

} // namespace

void detail::addDirectBounds(int power, const float *x, const float *y, const float *z,
                             const float *r, std::size_t count, const Box &box, float minD2,
                             double &low, double &high) {
    double lo = 0.0, hi = 0.0;
    (power == 1 ? directBounds1 : directBounds2)(x, y, z, r, count, box, minD2, 0.0f, lo, hi);
    // Float sums of positive terms, count / 8 per lane: each within that many roundings
    // (6e-8 each) of the exact sum; widened by twice that (and at least 1e-4) they stay bounds.
    const double widen = std::max(1e-4, 2.0 * 6e-8 * double(count / 8 + 8));
    low += lo * (1.0 - widen);
    high += hi * (1.0 + widen);
}

//-----------------------------------------------------------------------------
// [SECTION] Construction and the choice of cutoffs
//-----------------------------------------------------------------------------

MetaballField::MetaballField(const SphereSet &spheres, const SurfaceParams &params, float voxelSize,
                             const MultilevelTuning &tuning)
    : m_tree(spheres), m_params(params), m_tuning(tuning), m_h(voxelSize) {
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
            const int ratio =
                std::max(m_sparse ? std::max(m_tuning.minRatio, m_tuning.sparseMinRatio)
                                  : m_tuning.minRatio,
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
                         [](const Choice &a, const Choice &b) { return a.cost < b.cost; });
        std::optional<std::size_t> best;
        auto estimate = [&](Choice &c, double stopAbove) {
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
    const auto &s = m_tree.spheres();
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

void MetaballField::applyChoice(const CutoffChoice &c) {
    m_kappa = c.kappa;
    m_coarseKappa = c.coarse;
    m_ratio1 = c.ratio;
    m_a0 = static_cast<float>(c.kappa) * static_cast<float>(c.ratio) * m_h;
    m_soft0 = SoftenedKernel(m_kernel.p, m_a0, m_tuning.softeningOrder);
}

double MetaballField::weightWithin(const Vec3f &p, double a) const {
    const Box point{{p[0], p[1], p[2]}, {p[0], p[1], p[2]}};
    const float a2 = static_cast<float>(a * a);
    const auto &nodes = m_tree.nodes();
    const auto &s = m_tree.spheres();
    if (s.size() <= kDirectBoundsSpheres)
        return directWeightWithin(s.x.data(), s.y.data(), s.z.data(), s.r.data(), s.size(), p, a2);
    double sum = 0.0;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const auto &node = nodes[stack[--top]];
        if (detail::minDistance2(node.box, point) >= a2)
            continue;
        if (detail::maxDistance2(node.box, point) < a2) {
            sum += node.weight;
        } else if (!node.leaf()) {
            stack[top++] = node.left;
            stack[top++] = node.right;
        } else {
            for (std::uint32_t i = node.begin; i < node.end; ++i) {
                const float dx = s.x[i] - p[0], dy = s.y[i] - p[1], dz = s.z[i] - p[2];
                if (dx * dx + dy * dy + dz * dz < a2)
                    sum += s.r[i];
            }
        }
    }
    return sum;
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

std::array<double, 2> MetaballField::errorScale(std::map<double, double> *memo,
                                                std::vector<double> *terms,
                                                const std::array<double, 2> &weights,
                                                double stopAbove) const {
    // The densest weight within each cutoff over cutoff^p: the size of what each level
    // interpolates. [0]: level 1 (spacing a_0 / kappa), [1]: the coarser levels together.
    const auto &s = m_tree.spheres();
    const std::size_t n = s.size();
    const std::size_t samples = std::min<std::size_t>(n, 256);
    const auto &box = centreBox();
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
                [&](const tbb::blocked_range<std::size_t> &range, double most) {
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
    for (const auto &l : m_levels)
        n += l->neededCount();
    return n;
}

//-----------------------------------------------------------------------------
// [SECTION] Bounds over boxes
//-----------------------------------------------------------------------------

FieldBounds MetaballField::bounds(const Coord3 &lo, const Coord3 &hi, double isoMin, double isoMax,
                                  int maxOpen) const {
    const Box box = voxelBox(lo, hi, m_h);
    const BoundKernel k{m_params.kernel, m_kernel, m_params.compactReach};
    const auto &nodes = m_tree.nodes();
    const auto &s = m_tree.spheres();
    if (s.size() <= kDirectBoundsSpheres) {
        double low = 0.0, high = 0.0;
        const float invReach2 = 1.0f / (m_params.compactReach * m_params.compactReach);
        const auto direct = m_params.kernel == MetaballKernel::Compact ? directBounds0
                            : m_kernel.p == 1                          ? directBounds1
                                                                       : directBounds2;
        direct(s.x.data(), s.y.data(), s.z.data(), s.r.data(), s.size(), box, m_kernel.minD2,
               invReach2, low, high);
        // Float sums of positive terms, at most 512 per lane: each is within 512 roundings
        // (3.1e-5) of the exact sum, and each term within a few. Widened by more than that, they
        // stay bounds.
        return {low * (1.0 - 1e-4), high * (1.0 + 1e-4)};
    }
    struct Item {
        double gap; // weight * (kHigh - kLow): how much opening it can tighten the bounds
        double low, high;
        std::int32_t node;
        bool operator<(const Item &o) const { return gap < o.gap; }
    };
    auto itemFor = [&](std::int32_t index) {
        const auto &node = nodes[index];
        const float dmin2 = detail::minDistance2(node.box, box);
        if (m_params.kernel == MetaballKernel::Compact) {
            const float big = m_params.compactReach * node.rmax;
            if (dmin2 >= big * big)
                return Item{0.0, 0.0, 0.0, index};
        }
        const float dmax2 = detail::maxDistance2(node.box, box);
        const double low = double(node.weight) * k.value(dmax2, node.rmin);
        const double high = double(node.weight) * k.value(dmin2, node.rmax);
        return Item{high - low, low, high, index};
    };
    thread_local std::vector<Item> heap;
    heap.clear();
    const Item root = itemFor(0);
    double low = root.low, high = root.high;
    heap.push_back(root);
    for (int opened = 0; opened < maxOpen && !heap.empty(); ++opened) {
        if (low > isoMax || high < isoMin)
            break; // decided
        // Far from deciding either way after a few openings: the rest would be wasted (most
        // cells where the surface may pass). Giving up only keeps a cell; it never drops one.
        if (opened == m_tuning.probeOpen && high > m_tuning.giveUpRatio * isoMin &&
            low * m_tuning.giveUpRatio < isoMax)
            break;
        std::pop_heap(heap.begin(), heap.end());
        const Item item = heap.back();
        heap.pop_back();
        if (item.gap <= 0.0)
            break;
        low -= item.low;
        high -= item.high;
        const auto &node = nodes[item.node];
        if (node.leaf()) {
            for (std::uint32_t i = node.begin; i < node.end; ++i) {
                const Box centre{{s.x[i], s.y[i], s.z[i]}, {s.x[i], s.y[i], s.z[i]}};
                low += double(s.r[i]) * k.value(detail::maxDistance2(centre, box), s.r[i]);
                high += double(s.r[i]) * k.value(detail::minDistance2(centre, box), s.r[i]);
            }
            continue;
        }
        for (std::int32_t child : {node.left, node.right}) {
            const Item c = itemFor(child);
            low += c.low;
            high += c.high;
            if (c.gap > 0.0) {
                heap.push_back(c);
                std::push_heap(heap.begin(), heap.end());
            }
        }
    }
    return {low, high};
}

//-----------------------------------------------------------------------------
// [SECTION] Planning levels
//-----------------------------------------------------------------------------

void MetaballField::planLevels(std::span<const Coord3> blocks) {
    // Which nodes each level needs depends only on the level-1 spacing: levels already marked
    // for this ratio (by an earlier choice of cutoffs in this prepare()) are reused, only the
    // cutoffs and the top are decided again.
    if (m_markedRatio != m_ratio1) {
        m_levels.clear();
        m_spareLevels.clear();
        m_markedRatio = m_ratio1;
        // Mark the level-1 nodes every block needs (one voxel of margin, for mesh vertices).
        auto level1 = std::make_unique<FieldLevel>();
        level1->spacing = m_ratio1 * m_h;
        level1->ratio = m_ratio1;
        for (const auto &o : blocks) {
            detail::Int3 lo, hi;
            for (int k = 0; k < 3; ++k) {
                lo[k] = floorDiv(o[k] - 1, m_ratio1) - detail::kTapsBelow;
                hi[k] = floorDiv(o[k] + kBlockDim, m_ratio1) + detail::kTapsAbove;
            }
            level1->mark(lo, hi);
        }
        m_span2 = 0.0;
        const auto &cb = centreBox();
        for (int k = 0; k < 3; ++k) {
            double lo = cb.lo[k], hi = cb.hi[k];
            for (const auto &b : level1->bricks) {
                lo = std::min(lo, double(b.origin[k] + b.lo[k]) * level1->spacing);
                hi = std::max(hi, double(b.origin[k] + b.hi[k]) * level1->spacing);
            }
            m_span2 += (hi - lo) * (hi - lo);
        }
        m_levels.push_back(std::move(level1));
    }
    // Levels above the last choice's top wait in m_spareLevels.
    for (auto &spare : m_spareLevels)
        m_levels.push_back(std::move(spare));
    m_spareLevels.clear();
    for (auto &level : m_levels)
        level->top = false;
    const double n = static_cast<double>(sphereCount());
    const double span2 = m_span2;
    for (int l = 1;; ++l) {
        FieldLevel &level = *m_levels[l - 1];
        const float aBelow = static_cast<float>(cutoff(l - 1));
        level.below =
            l == 1 ? m_soft0 : SoftenedKernel(m_kernel.p, aBelow, m_tuning.softeningOrder);
        level.cutoff = static_cast<float>(cutoff(l));
        level.own = SoftenedKernel(m_kernel.p, level.cutoff, m_tuning.softeningOrder);
        // Top: summing all spheres is cheap, or every sphere lies within the cutoff of every
        // point the voxels need, or summing them all here costs less than this level's windowed
        // sums and those of the levels above would (about one such level per doubling of the
        // cutoff up to the span).
        const double needed = static_cast<double>(level.neededCount());
        bool cheaperOnTop = false;
        if (m_tuning.topByCost && needed * n > m_tuning.topLevelPairs && !level.bricks.empty()) {
            double window = 0.0;
            int samples = 0;
            const std::size_t stride = std::max<std::size_t>(1, level.bricks.size() / 32);
            for (std::size_t bi = 0; bi < level.bricks.size(); bi += stride) {
                const Brick &b = level.bricks[bi];
                for (int off = 0; off < 512; ++off)
                    if (b.needed(off)) {
                        const Vec3f p{(b.origin[0] + (off >> 6)) * level.spacing,
                                      (b.origin[1] + ((off >> 3) & 7)) * level.spacing,
                                      (b.origin[2] + (off & 7)) * level.spacing};
                        window += weightWithin(p, level.cutoff) * n / totalWeight();
                        ++samples;
                        break;
                    }
            }
            const double levelsLeft =
                1.0 + std::max(0.0, std::log2(std::sqrt(span2) / double(level.cutoff)));
            // A node's group list holds about twice its window (measured on the bench zone).
            constexpr double kListOverWindow = 2.0;
            cheaperOnTop = samples > 0 && n <= kListOverWindow * window / samples * levelsLeft;
        }
        if (needed * n <= m_tuning.topLevelPairs || cheaperOnTop ||
            double(aBelow) * aBelow >= span2 || l >= 30) {
            level.top = true;
            for (std::size_t above = l; above < m_levels.size(); ++above)
                m_spareLevels.push_back(std::move(m_levels[above]));
            m_levels.resize(l);
            break;
        }
        if (static_cast<std::size_t>(l) < m_levels.size())
            continue; // marked before
        auto next = std::make_unique<FieldLevel>();
        next->spacing = 2.0f * level.spacing;
        next->ratio = 2;
        for (const auto &b : level.bricks) {
            detail::Int3 lo, hi;
            for (int k = 0; k < 3; ++k) {
                lo[k] = floorDiv(b.origin[k] + b.lo[k], 2) - detail::kTapsBelow;
                hi[k] = floorDiv(b.origin[k] + b.hi[k], 2) + detail::kTapsAbove;
            }
            next->mark(lo, hi);
        }
        m_levels.push_back(std::move(next));
    }
}

double MetaballField::levelsEstimate() const {
    if (m_errorTerms.empty())
        return 0.0;
    const auto weights = errorWeights(m_kappa, m_coarseKappa, m_kernel.p);
    double estimate = weights[0] * errorTerm(0);
    for (int l = 1; l < levelCount(); ++l)
        estimate += weights[1] * errorTerm(l);
    return estimate;
}

double MetaballField::errorTerm(int l) const {
    // A level beyond the terms has a cutoff over twice the span: the last term bounds its.
    return m_errorTerms[std::min<std::size_t>(l, m_errorTerms.size() - 1)];
}

//-----------------------------------------------------------------------------
// [SECTION] Preparing the levels for planned blocks
//-----------------------------------------------------------------------------

void MetaballField::prepare(std::span<const Coord3> blocks, Interrupter *interrupter) {
    m_blocks.clear();
    m_blockOrigins.assign(blocks.begin(), blocks.end());
    for (std::size_t i = 0; i < blocks.size(); ++i)
        m_blocks.emplace(packKey({floorDiv(blocks[i][0], 8), floorDiv(blocks[i][1], 8),
                                  floorDiv(blocks[i][2], 8)}),
                         static_cast<std::uint32_t>(i));
    m_levels.clear();
    m_spareLevels.clear();
    m_markedRatio = 0;
    if (m_params.kernel == MetaballKernel::Compact || blocks.empty())
        return;

    // The constructor's estimate assumed coarse levels up to twice the span; with the levels
    // these blocks need (often fewer), a cheaper pair of cutoffs may fit the budget. The cheapest
    // that does is the choice (level 1's term alone, a lower bound, skips most without planning).
    const CutoffChoice chosen{m_kappa, m_coarseKappa, m_ratio1, m_estimatedError, 0.0};
    const double budget = errorBudget(m_params);
    bool cheaper = false;
    for (const CutoffChoice &c : m_cheaper) {
        applyChoice(c);
        std::vector<double> terms;
        errorScale(&m_densest, &terms);
        const auto weights = errorWeights(c.kappa, c.coarse, m_kernel.p);
        if (weights[0] * terms[0] > budget)
            continue;
        std::swap(terms, m_errorTerms);
        planLevels(blocks);
        if (levelsEstimate() <= budget) {
            cheaper = true;
            break;
        }
        std::swap(terms, m_errorTerms);
    }
    if (!cheaper) {
        applyChoice(chosen);
        planLevels(blocks);
    }
    m_cheaper.clear(); // prepared once
    m_spareLevels.clear();

    // The error of this hierarchy: level 1's interpolation and each coarser level's (the top
    // level's values are exact sums, with nothing above to interpolate). Then from the top down,
    // a level sums grid charges instead of spheres while that (a second interpolation error of
    // the same size, on the spheres' side) fits the budget and the charges are few enough.
    const int levelCount = static_cast<int>(m_levels.size());
    std::vector<std::optional<ChargeGrid>> charges(m_levels.size());
    m_anterpolated = 0;
    if (!m_errorTerms.empty()) {
        const auto weights = errorWeights(m_kappa, m_coarseKappa, m_kernel.p);
        double estimate = levelsEstimate();
        if (m_tuning.anterpolateFrom > 0)
            for (int l = levelCount; l >= std::max(2, m_tuning.anterpolateFrom); --l) {
                const double extra = weights[1] * errorTerm(l - 1);
                if (estimate + extra > errorBudget(m_params))
                    break;
                auto grid = anterpolate(m_tree.spheres(), centreBox(), m_levels[l - 1]->spacing);
                if (!grid || double(grid->nonzero) > m_tuning.chargeShare * double(sphereCount()))
                    break;
                charges[l - 1] = std::move(grid);
                estimate += extra;
                ++m_anterpolated;
            }
        m_estimatedError = estimate;
    }

    // A top level with charges sums all of them: one list for all its nodes.
    WindowList topCharges;
    if (!charges.empty() && charges.back())
        charges.back()->gather(charges.back()->lo, 1, std::numeric_limits<float>::infinity(),
                               topCharges);

    // Compute from the coarsest level down: each level adds its window sum to the cubic
    // interpolation of the level above.
    std::size_t totalBricks = 0;
    for (const auto &l : m_levels)
        totalBricks += l->bricks.size();
    std::atomic<std::size_t> done{0};
    std::atomic<bool> cancelled{false};
    const auto &s = m_tree.spheres();
    const InverseKernel kernel = m_kernel;
    for (int li = static_cast<int>(m_levels.size()) - 1; li >= 0; --li) {
        FieldLevel &level = *m_levels[li];
        const FieldLevel *above =
            li + 1 < static_cast<int>(m_levels.size()) ? m_levels[li + 1].get() : nullptr;
        const WindowKernels kernels(level.below, level.own, kernel.minD2);
        tbb::parallel_for(std::size_t{0}, level.bricks.size(), [&](std::size_t bi) {
            if (cancelled.load(std::memory_order_relaxed))
                return;
            Brick &brick = level.bricks[bi];
            // Nodes in 4^3 groups, each with its own sphere ranges: the window (a ball of radius
            // a_l) fills more of a small group's box than of the whole brick's.
            constexpr int kGroup = 4;
            for (int gi = brick.lo[0] & ~(kGroup - 1); gi <= brick.hi[0]; gi += kGroup)
                for (int gj = brick.lo[1] & ~(kGroup - 1); gj <= brick.hi[1]; gj += kGroup)
                    for (int gz = brick.lo[2] & ~(kGroup - 1); gz <= brick.hi[2]; gz += kGroup) {
                        int needed[kGroup * kGroup * kGroup], count = 0;
                        for (int c = 0; c < kGroup * kGroup * kGroup; ++c) {
                            const int off =
                                Brick::offset(gi + c / (kGroup * kGroup),
                                              gj + (c / kGroup) % kGroup, gz + c % kGroup);
                            if (brick.needed(off))
                                needed[count++] = off;
                        }
                        if (count == 0)
                            continue;
                        // What every node of the group sums, contiguous: all spheres at the top
                        // level (straight from the tree's arrays) or all its charges, else the
                        // spheres or charges of the window, gathered once per group and padded.
                        const float *px = s.x.data(), *py = s.y.data(), *pz = s.z.data(),
                                    *pw = s.r.data();
                        std::size_t len = s.size();
                        const ChargeGrid *grid = charges[li] ? &*charges[li] : nullptr;
                        const int g[3] = {gi, gj, gz};
                        thread_local WindowList window;
                        if (grid && level.top) {
                            px = topCharges.x.data(), py = topCharges.y.data();
                            pz = topCharges.z.data(), pw = topCharges.w.data();
                            len = topCharges.w.size();
                        } else if (grid || !level.top) {
                            if (grid) {
                                grid->gather({brick.origin[0] + g[0], brick.origin[1] + g[1],
                                              brick.origin[2] + g[2]},
                                             kGroup, level.cutoff, window);
                            } else {
                                thread_local std::vector<std::pair<std::uint32_t, std::uint32_t>>
                                    ranges;
                                ranges.clear();
                                Box box;
                                for (int k = 0; k < 3; ++k) {
                                    box.lo[k] = (brick.origin[k] + g[k]) * level.spacing;
                                    box.hi[k] =
                                        (brick.origin[k] + g[k] + kGroup - 1) * level.spacing;
                                }
                                m_tree.gatherRanges(box, level.cutoff, ranges);
                                window.clear();
                                for (const auto &range : ranges) {
                                    auto copy = [&](const std::vector<float> &from,
                                                    std::vector<float> &to) {
                                        to.insert(to.end(), from.begin() + range.first,
                                                  from.begin() + range.second);
                                    };
                                    copy(s.x, window.x), copy(s.y, window.y);
                                    copy(s.z, window.z), copy(s.r, window.w);
                                }
                                window.pad();
                            }
                            px = window.x.data(), py = window.y.data(), pz = window.z.data();
                            pw = window.w.data();
                            len = window.w.size();
                        }
                        for (int n = 0; n < count; ++n) {
                            const int off = needed[n];
                            const int i = off >> 6, j = (off >> 3) & 7, z = off & 7;
                            const float x = (brick.origin[0] + i) * level.spacing;
                            const float y = (brick.origin[1] + j) * level.spacing;
                            const float w = (brick.origin[2] + z) * level.spacing;
                            brick.values[off] =
                                kernel.p == 2
                                    ? windowSum2(x, y, w, px, py, pz, pw, len, kernels, level.top)
                                    : windowSum1(x, y, w, px, py, pz, pw, len, kernels, level.top);
                        }
                    }
            if (above) {
                const detail::Int3 t0{brick.origin[0] + brick.lo[0], brick.origin[1] + brick.lo[1],
                                      brick.origin[2] + brick.lo[2]};
                const detail::Int3 nn{brick.hi[0] - brick.lo[0] + 1, brick.hi[1] - brick.lo[1] + 1,
                                      brick.hi[2] - brick.lo[2] + 1};
                thread_local std::vector<float> interp;
                interp.assign(static_cast<std::size_t>(nn[0]) * nn[1] * nn[2], 0.0f);
                detail::addInterpolated(*above, 2, t0, nn, interp.data());
                for (int i = 0; i < nn[0]; ++i)
                    for (int j = 0; j < nn[1]; ++j)
                        for (int z = 0; z < nn[2]; ++z) {
                            const int off =
                                Brick::offset(brick.lo[0] + i, brick.lo[1] + j, brick.lo[2] + z);
                            if (brick.needed(off))
                                brick.values[off] += interp[(i * nn[1] + j) * nn[2] + z];
                        }
            }
            const std::size_t d = ++done;
            if (interrupter && interrupter->wasInterrupted(static_cast<int>(100 * d / totalBricks)))
                cancelled = true;
        });
        if (cancelled)
            throw SurfaceCancelled();
    }
}

//-----------------------------------------------------------------------------
// [SECTION] Evaluating blocks
//-----------------------------------------------------------------------------

void MetaballField::evaluateColor(const Coord3 &o, Vec3f *color) const {
    thread_local NearList colors;
    const Box box = blockBox(o, m_h);
    colors.clear();
    m_tree.gather(box, maxRadius() + m_params.colorReach, colors, true);
    static_assert(kBlockDim == 8, "colorRow fills rows of 8 voxels");
    if (colors.size() == 0) {
        std::fill(color, color + kBlockVoxels, m_params.initialColor);
        return;
    }
    for (int i = 0; i < kBlockDim; ++i)
        for (int j = 0; j < kBlockDim; ++j) {
            float red[8], green[8], blue[8], n[8];
            colorRow((o[0] + i) * m_h, (o[1] + j) * m_h, o[2], m_h, colors,
                     m_params.colorReach, red, green, blue, n);
            for (int k = 0; k < kBlockDim; ++k)
                color[blockOffset(i, j, k)] =
                    n[k] > 0.0f ? Vec3f{red[k] / n[k], green[k] / n[k], blue[k] / n[k]}
                                : m_params.initialColor;
        }
}

void MetaballField::evaluateBlock(const Coord3 &o, float *density, Vec3f *color) const {
    // One tree walk per block for the spheres within a0, then one list per 4^3 octant filtered
    // from it (shorter lists than the block's); the colour has its own far shorter list: only
    // spheres whose radius + reach can hold a voxel of the block.
    thread_local NearList block;
    gatherNear(o, block);
    if (color)
        evaluateColor(o, color);
    nearValues(o, block, density);
    if (!m_levels.empty())
        detail::addInterpolated(*m_levels.front(), m_ratio1, o, {8, 8, 8}, density);
}

int MetaballField::evaluateBlockUnlessOneSided(const Coord3 &o, float *density, float isoMin,
                                               float isoMax, FieldBounds *bounds) const {
    if (m_params.kernel == MetaballKernel::Compact || m_levels.empty()) {
        evaluateBlock(o, density, nullptr);
        return 0;
    }
    // The coarse levels' part, exactly as evaluateBlock adds it.
    float smooth[kBlockVoxels] = {};
    detail::addInterpolated(*m_levels.front(), m_ratio1, o, {8, 8, 8}, smooth);
    float smoothLo = smooth[0], smoothHi = smooth[0];
    for (float v : smooth) {
        smoothLo = std::min(smoothLo, v);
        smoothHi = std::max(smoothHi, v);
    }
    // The near part, k - gamma_a0 within a0, lies in [0, k(dmin) - gamma_a0(dmax)] over the
    // block for each sphere: gamma is positive and decreasing in d, and below k where the
    // softening's order is even (its Taylor remainder is then positive).
    thread_local NearList block;
    gatherNear(o, block);
    const Box box = blockBox(o, m_h);
    const float a2 = m_a0 * m_a0;
    // With an even order also at least k(dmax) - gamma_a0(dmin) where the block lies within a0.
    const bool evenOrder = m_tuning.softeningOrder % 2 == 0;
    double nearLo = 0.0, nearHi = 0.0;
    for (std::size_t q = 0; q < block.size(); ++q) {
        const Box centre{{block.x[q], block.y[q], block.z[q]}, {block.x[q], block.y[q], block.z[q]}};
        const float near2 = detail::minDistance2(centre, box);
        if (near2 >= a2)
            continue;
        const float far2 = detail::maxDistance2(centre, box);
        nearHi += double(block.r[q]) *
                  (double(m_kernel.value(near2)) - m_soft0.inner(std::min(far2, a2)));
        if (evenOrder && far2 < a2)
            nearLo += double(block.r[q]) *
                      std::max(0.0, double(m_kernel.value(far2)) - m_soft0.inner(near2));
    }
    // Float rounding of 512 sums: within 1e-4 of the larger of them.
    const double slack = 1e-4 * (std::abs(double(smoothHi)) + nearHi);
    const double low = double(smoothLo) + nearLo - slack, high = double(smoothHi) + nearHi + slack;
    const int side = high < isoMin ? -1 : evenOrder && low > isoMax ? 1 : 0;
    if (side != 0) {
        *bounds = {low, high};
        return side;
    }
    nearValues(o, block, density);
    for (int n = 0; n < kBlockVoxels; ++n)
        density[n] += smooth[n];
    return 0;
}

//-----------------------------------------------------------------------------
// [SECTION] Near field and points
//-----------------------------------------------------------------------------

void MetaballField::gatherNear(const Coord3 &o, NearList &block) const {
    const Box box = blockBox(o, m_h);
    block.clear();
    m_tree.gather(box, m_a0, block, false);
}

void MetaballField::nearValues(const Coord3 &o, const NearList &block, float *density) const {
    const float a2 = m_a0 * m_a0;
    const bool compact = m_params.kernel == MetaballKernel::Compact;
    const float invC2 = 1.0f / (m_params.compactReach * m_params.compactReach);
    const Box box = blockBox(o, m_h);
    // Each sphere's gap to the lower and upper half of the block along each axis gives its
    // distance to all eight octants in one pass.
    constexpr int kHalf = kBlockDim / 2;
    thread_local NearList octants[8];
    for (auto &l : octants)
        l.clear();
    for (std::size_t q = 0; q < block.size(); ++q) {
        const float c[3] = {block.x[q], block.y[q], block.z[q]};
        float gap2[3][2];
        for (int k = 0; k < 3; ++k) {
            const float lowHi = (o[k] + kHalf - 1) * m_h, highLo = (o[k] + kHalf) * m_h;
            const float low = std::max({box.lo[k] - c[k], c[k] - lowHi, 0.0f});
            const float high = std::max({highLo - c[k], c[k] - box.hi[k], 0.0f});
            gap2[k][0] = low * low;
            gap2[k][1] = high * high;
        }
        for (int octant = 0; octant < 8; ++octant) {
            if (gap2[0][octant & 1] + gap2[1][(octant >> 1) & 1] + gap2[2][(octant >> 2) & 1] >
                a2)
                continue;
            NearList &l = octants[octant];
            l.x.push_back(c[0]), l.y.push_back(c[1]), l.z.push_back(c[2]);
            l.r.push_back(block.r[q]);
        }
    }
    for (int octant = 0; octant < 8; ++octant) {
        const Coord3 lo{o[0] + (octant & 1) * kHalf, o[1] + ((octant >> 1) & 1) * kHalf,
                        o[2] + ((octant >> 2) & 1) * kHalf};
        NearList &list = octants[octant];
        padToVectors(list);
        for (int i = 0; i < kHalf; ++i)
            for (int j = 0; j < kHalf; ++j)
                for (int k = 0; k < kHalf; ++k) {
                    const float x = (lo[0] + i) * m_h, y = (lo[1] + j) * m_h, z = (lo[2] + k) * m_h;
                    const float minD2 = m_kernel.minD2;
                    const float f = compact ? nearValue0(x, y, z, list, invC2, a2, minD2, m_soft0)
                                    : m_kernel.p == 2
                                        ? nearValue2(x, y, z, list, invC2, a2, minD2, m_soft0)
                                        : nearValue1(x, y, z, list, invC2, a2, minD2, m_soft0);
                    density[blockOffset(lo[0] - o[0] + i, lo[1] - o[1] + j, lo[2] - o[2] + k)] =
                        f;
                }
    }
}

namespace {

// Near field and its analytic gradient (Algorithm 1 line 8) at one point.
template <int P>
[[gnu::always_inline]] inline void nearGradientBody(const NearList &list, const Vec3f &p, float a2,
                                                    float minD2, float invC2,
                                                    const SoftenedKernel &soft, float out[4]) {
    const std::size_t count = list.size();
    const float *lx = list.x.data();
    const float *ly = list.y.data();
    const float *lz = list.z.data();
    const float *lr = list.r.data();
    const float invSoft = 1.0f / soft.a2;
    float f = 0.0f, gx = 0.0f, gy = 0.0f, gz = 0.0f;
#pragma omp simd reduction(+ : f, gx, gy, gz)
    for (std::size_t q = 0; q < count; ++q) {
        const float dx = p[0] - lx[q], dy = p[1] - ly[q], dz = p[2] - lz[q];
        const float d2 = dx * dx + dy * dy + dz * dz;
        float v, slope;
        if constexpr (P == 0) {
            const float inv = invC2 / (lr[q] * lr[q]);
            v = compactValue(d2, inv);
            slope = compactSlope(d2, inv);
        } else {
            const float dc = d2 < minD2 ? minD2 : d2;
            const float k = inversePower<P>(dc, minD2);
            // dk/d(d^2) = -(P/2) k / d^2, zero where the distance is clamped.
            const float kSlope = d2 < minD2 ? 0.0f : -0.5f * float(P) * k / dc;
            const float t = d2 * invSoft - 1.0f;
            const float softSlope =
                soft.scale * invSoft *
                (soft.coef[1] +
                 t * (2.0f * soft.coef[2] + t * (3.0f * soft.coef[3] + t * 4.0f * soft.coef[4])));
            const bool in = d2 < a2;
            v = in ? k - softInner(soft, invSoft, d2) : 0.0f;
            slope = in ? kSlope - softSlope : 0.0f;
        }
        f += lr[q] * v;
        const float g = 2.0f * lr[q] * slope;
        gx += g * dx;
        gy += g * dy;
        gz += g * dz;
    }
    out[0] = f;
    out[1] = gx;
    out[2] = gy;
    out[3] = gz;
}

FAULTLINE_HOT void nearGradient0(const NearList &list, const Vec3f &p, float a2, float minD2,
                                 float invC2, const SoftenedKernel &soft, float out[4]) {
    nearGradientBody<0>(list, p, a2, minD2, invC2, soft, out);
}
FAULTLINE_HOT void nearGradient1(const NearList &list, const Vec3f &p, float a2, float minD2,
                                 float invC2, const SoftenedKernel &soft, float out[4]) {
    nearGradientBody<1>(list, p, a2, minD2, invC2, soft, out);
}
FAULTLINE_HOT void nearGradient2(const NearList &list, const Vec3f &p, float a2, float minD2,
                                 float invC2, const SoftenedKernel &soft, float out[4]) {
    nearGradientBody<2>(list, p, a2, minD2, invC2, soft, out);
}

} // namespace

void MetaballField::sumNear(const NearList &list, const Vec3f &p, float &value, Vec3f *gradient,
                            Vec3f *color) const {
    (void)color;
    const float a2 = m_a0 * m_a0;
    const float invC2 = 1.0f / (m_params.compactReach * m_params.compactReach);
    float out[4];
    if (m_params.kernel == MetaballKernel::Compact)
        nearGradient0(list, p, a2, m_kernel.minD2, invC2, m_soft0, out);
    else if (m_kernel.p == 2)
        nearGradient2(list, p, a2, m_kernel.minD2, invC2, m_soft0, out);
    else
        nearGradient1(list, p, a2, m_kernel.minD2, invC2, m_soft0, out);
    value += out[0];
    if (gradient)
        *gradient = {(*gradient)[0] + out[1], (*gradient)[1] + out[2], (*gradient)[2] + out[3]};
}

void MetaballField::evaluatePoints(std::span<const Vec3f> points, float *values,
                                   Vec3f *gradients) const {
    // Group the points by a prepared block next to them: one neighbour list and one coarse
    // patch per group.
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> groups;
    std::vector<std::uint32_t> orphans;
    for (std::size_t n = 0; n < points.size(); ++n) {
        const auto &p = points[n];
        int cell[3];
        for (int k = 0; k < 3; ++k)
            cell[k] = static_cast<int>(std::floor(p[k] / m_h));
        bool found = false;
        for (int corner = 0; corner < 8 && !found; ++corner) {
            const detail::Int3 v{cell[0] + (corner & 1), cell[1] + ((corner >> 1) & 1),
                                 cell[2] + ((corner >> 2) & 1)};
            auto it =
                m_blocks.find(packKey({floorDiv(v[0], 8), floorDiv(v[1], 8), floorDiv(v[2], 8)}));
            if (it != m_blocks.end()) {
                groups[it->second].push_back(static_cast<std::uint32_t>(n));
                found = true;
            }
        }
        if (!found)
            orphans.push_back(static_cast<std::uint32_t>(n));
    }
    std::vector<const std::vector<std::uint32_t> *> groupList;
    std::vector<std::uint32_t> groupBlock;
    for (const auto &[block, members] : groups) {
        groupList.push_back(&members);
        groupBlock.push_back(block);
    }
    tbb::parallel_for(std::size_t{0}, groupList.size(), [&](std::size_t g) {
        const auto &members = *groupList[g];
        const Coord3 origin = m_blockOrigins[groupBlock[g]];
        thread_local NearList list;
        list.clear();
        const Box box = voxelBox({origin[0] - 1, origin[1] - 1, origin[2] - 1},
                                 {origin[0] + 8, origin[1] + 8, origin[2] + 8}, m_h);
        m_tree.gather(box, m_a0, list, false);
        thread_local std::vector<float> patch;
        detail::Int3 s0{0, 0, 0}, sd{0, 0, 0};
        const FieldLevel *level1 = m_levels.empty() ? nullptr : m_levels.front().get();
        if (level1) {
            for (int k = 0; k < 3; ++k) {
                s0[k] = floorDiv(origin[k] - 1, m_ratio1) - detail::kTapsBelow;
                sd[k] = floorDiv(origin[k] + 8, m_ratio1) + detail::kTapsAbove - s0[k] + 1;
            }
            detail::gatherPatch(*level1, s0, sd, patch);
        }
        for (std::uint32_t n : members) {
            const Vec3f &p = points[n];
            float value = 0.0f;
            Vec3f grad{0, 0, 0};
            sumNear(list, p, value, &grad, nullptr);
            if (level1) {
                constexpr int nt = detail::kTaps;
                float w[3][nt], dw[3][nt];
                int b[3];
                for (int k = 0; k < 3; ++k) {
                    const float t = p[k] / level1->spacing;
                    const float fl = std::floor(t);
                    b[k] = static_cast<int>(fl) - detail::kTapsBelow - s0[k];
                    assert(b[k] >= 0 && b[k] + nt <= sd[k]);
                    b[k] = std::clamp(b[k], 0, sd[k] - nt);
                    detail::lagrangeWeights(t - fl, w[k]);
                    detail::lagrangeDerivatives(t - fl, dw[k]);
                }
                // Separable: contract z, then y, then x, carrying the derivative weights.
                float sz[nt][nt], dz[nt][nt];
                for (int i = 0; i < nt; ++i)
                    for (int j = 0; j < nt; ++j) {
                        const float *row =
                            &patch[(static_cast<std::size_t>(b[0] + i) * sd[1] + b[1] + j) * sd[2] +
                                   b[2]];
                        float a = 0.0f, d = 0.0f;
                        for (int z = 0; z < nt; ++z) {
                            a += w[2][z] * row[z];
                            d += dw[2][z] * row[z];
                        }
                        sz[i][j] = a;
                        dz[i][j] = d;
                    }
                float v = 0.0f, g0 = 0.0f, g1 = 0.0f, g2 = 0.0f;
                for (int i = 0; i < nt; ++i) {
                    float a = 0.0f, dy = 0.0f, dzy = 0.0f;
                    for (int j = 0; j < nt; ++j) {
                        a += w[1][j] * sz[i][j];
                        dy += dw[1][j] * sz[i][j];
                        dzy += w[1][j] * dz[i][j];
                    }
                    v += w[0][i] * a;
                    g0 += dw[0][i] * a;
                    g1 += w[0][i] * dy;
                    g2 += w[0][i] * dzy;
                }
                const float inv = 1.0f / level1->spacing;
                value += v;
                grad = {grad[0] + g0 * inv, grad[1] + g1 * inv, grad[2] + g2 * inv};
            }
            if (values)
                values[n] = value;
            if (gradients)
                gradients[n] = grad;
        }
    });
    // Points away from every prepared block: sum every sphere (rare; correct, slow).
    const auto &s = m_tree.spheres();
    for (std::uint32_t n : orphans) {
        const Vec3f &p = points[n];
        float value = 0.0f;
        Vec3f grad{0, 0, 0};
        for (std::size_t q = 0; q < s.size(); ++q) {
            const float dx = p[0] - s.x[q], dy = p[1] - s.y[q], dz = p[2] - s.z[q];
            const float d2 = dx * dx + dy * dy + dz * dz;
            float v, slope;
            if (m_params.kernel == MetaballKernel::Compact) {
                const float big = m_params.compactReach * s.r[q];
                v = compactValue(d2, 1.0f / (big * big));
                slope = compactSlope(d2, 1.0f / (big * big));
            } else {
                v = m_kernel.value(d2);
                slope = d2 < m_kernel.minD2 ? 0.0f : m_kernel.slope(d2);
            }
            value += s.r[q] * v;
            const float g = 2.0f * s.r[q] * slope;
            grad = {grad[0] + g * dx, grad[1] + g * dy, grad[2] + g * dz};
        }
        if (values)
            values[n] = value;
        if (gradients)
            gradients[n] = grad;
    }
}

} // namespace faultline::core
