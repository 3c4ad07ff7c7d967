// MetaballField, evaluation (see metaball_field.cpp for the algorithm): blocks of voxels (the
// levels interpolated plus the near sums), colours, and single points with gradients.
//
// Index of this file:
// [SECTION] Evaluating blocks
// [SECTION] Near field and points

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

namespace {

// The near sums of one 4^3 octant of a block (its first voxel at index lo), voxels in the
// vector lanes and one sphere at a time: lane l of vector (i, half) is voxel
// (i, 2 half + l / 4, l % 4) of the octant, and out[8 (2 i + half) + l] its sum. Octant lists
// are short for sparse sets (a few to a few dozen spheres): one voxel per call with the spheres
// in the lanes spent more on the call, the horizontal sum and the padding of the last vector
// than on the terms (spread-out r/2 set: near sums 3.3x faster for r/d, 1.5x for r/d^2).
template <int P>
[[gnu::always_inline]] inline void octantNearBody(const int lo[3], float h, const NearList& list,
                                                  const unsigned char* reach, unsigned octant,
                                                  float invC2, float a2, float minD2,
                                                  const SoftenedKernel& soft, float out[64]) {
    using simd8::splat;
    using simd8::v8f;
    const v8f one = splat(1.0f), va2 = splat(a2), vmin = splat(minD2),
              vinvSoft = splat(1.0f / soft.a2);
    v8f c[5];
    for (int k = 0; k < 5; ++k)
        c[k] = splat(soft.scale * soft.coef[k]);
    v8f laneY[2], laneZ;
    for (int l = 0; l < 8; ++l) {
        laneY[0][l] = float(lo[1] + l / 4) * h;
        laneY[1][l] = float(lo[1] + 2 + l / 4) * h;
        laneZ[l] = float(lo[2] + l % 4) * h;
    }
    const std::size_t count = list.size();
    const float *px = list.x.data(), *py = list.y.data(), *pz = list.z.data(), *pr = list.r.data();
    float xs[4];
    for (int i = 0; i < 4; ++i)
        xs[i] = float(lo[0] + i) * h;
    // Per sphere, its squared distance in y and z to the eight lanes once; then each of the
    // four x planes adds its own (a scalar).
    for (int half = 0; half < 2; ++half) {
        v8f acc[4] = {};
        for (std::size_t q = 0; q < count; ++q) {
            if (!((reach[q] >> octant) & 1u))
                continue; // beyond a0 of every voxel of this octant
            const v8f dy = laneY[half] - splat(py[q]), dz = laneZ - splat(pz[q]);
            const v8f yz2 = dy * dy + dz * dz, r = splat(pr[q]);
            [[maybe_unused]] const v8f compactScale =
                splat(P == 0 ? invC2 / (pr[q] * pr[q]) : 0.0f);
            for (int i = 0; i < 4; ++i) {
                const float dx = xs[i] - px[q];
                const v8f d2 = yz2 + splat(dx * dx);
                if constexpr (P == 0) {
                    const v8f t = one - d2 * compactScale;
                    acc[i] += t > v8f{} ? r * (t * t * t) : v8f{};
                } else {
                    const v8f clamped = simd8::max(d2, vmin);
                    v8f k;
                    if constexpr (P == 2)
                        k = one / clamped;
                    else
                        k = simd8::inverseSqrt(clamped);
                    const v8f t = d2 * vinvSoft - one;
                    const v8f v = k - (c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * c[4]))));
                    acc[i] += d2 < va2 ? r * v : v8f{};
                }
            }
        }
        for (int i = 0; i < 4; ++i)
            simd8::store(out + 8 * (2 * i + half), acc[i]);
    }
}

FAULTLINE_HOT void octantNear0(const int lo[3], float h, const NearList& list,
                               const unsigned char* reach, unsigned octant, float invC2, float a2,
                               float minD2, const SoftenedKernel& soft, float out[64]) {
    octantNearBody<0>(lo, h, list, reach, octant, invC2, a2, minD2, soft, out);
}
FAULTLINE_HOT void octantNear1(const int lo[3], float h, const NearList& list,
                               const unsigned char* reach, unsigned octant, float invC2, float a2,
                               float minD2, const SoftenedKernel& soft, float out[64]) {
    octantNearBody<1>(lo, h, list, reach, octant, invC2, a2, minD2, soft, out);
}
FAULTLINE_HOT void octantNear2(const int lo[3], float h, const NearList& list,
                               const unsigned char* reach, unsigned octant, float invC2, float a2,
                               float minD2, const SoftenedKernel& soft, float out[64]) {
    octantNearBody<2>(lo, h, list, reach, octant, invC2, a2, minD2, soft, out);
}

// Bounds of the near part over a box, 8 spheres at a time (see evaluateBlockUnlessOneSided):
// per sphere within a0 of the box, [k(far) - gamma(near)]+ (only where the box lies within a0
// and `lower`) and k(near) - gamma(min(far, a0)), summed into lo and hi.
template <int P>
[[gnu::always_inline]] inline void nearBoundsBody(const NearList& list, const Box& box, float a2,
                                                  float minD2, const SoftenedKernel& soft,
                                                  bool lower, float& lo, float& hi) {
    using simd8::splat;
    using simd8::v8f;
    const v8f va2 = splat(a2), vmin = splat(minD2), one = splat(1.0f),
              invSoft = splat(1.0f / soft.a2);
    v8f c[5];
    for (int k = 0; k < 5; ++k)
        c[k] = splat(soft.scale * soft.coef[k]);
    const v8f blo[3] = {splat(box.lo[0]), splat(box.lo[1]), splat(box.lo[2])};
    const v8f bhi[3] = {splat(box.hi[0]), splat(box.hi[1]), splat(box.hi[2])};
    v8f accLo{}, accHi{};
    const std::size_t count = list.size();
    for (std::size_t q = 0; q < count; q += 8) {
        const std::size_t n = count - q;
        const v8f pos[3] = {simd8::loadUpTo(list.x.data() + q, n),
                            simd8::loadUpTo(list.y.data() + q, n),
                            simd8::loadUpTo(list.z.data() + q, n)};
        const v8f r = simd8::loadUpTo(list.r.data() + q, n); // 0 past the end
        v8f near2{}, far2{};
        for (int k = 0; k < 3; ++k) {
            const v8f gap = simd8::max(simd8::max(blo[k] - pos[k], pos[k] - bhi[k]), v8f{});
            const v8f span = simd8::max(pos[k] - blo[k], bhi[k] - pos[k]);
            near2 += gap * gap;
            far2 += span * span;
        }
        // k at the nearest and farthest points, gamma's polynomial at the farthest point
        // within a0 and at the nearest.
        v8f kNear, kFar;
        if constexpr (P == 2) {
            kNear = one / simd8::max(near2, vmin);
            kFar = one / simd8::max(far2, vmin);
        } else {
            kNear = simd8::inverseSqrt(simd8::max(near2, vmin));
            kFar = simd8::inverseSqrt(simd8::max(far2, vmin));
        }
        const v8f tFar = (far2 < va2 ? far2 : va2) * invSoft - one, tNear = near2 * invSoft - one;
        const v8f gFar = c[0] + tFar * (c[1] + tFar * (c[2] + tFar * (c[3] + tFar * c[4])));
        const v8f gNear = c[0] + tNear * (c[1] + tNear * (c[2] + tNear * (c[3] + tNear * c[4])));
        const auto reaches = near2 < va2;
        accHi += reaches ? r * (kNear - gFar) : v8f{};
        if (lower)
            accLo += reaches && far2 < va2 ? r * simd8::max(kFar - gNear, v8f{}) : v8f{};
    }
    lo = simd8::sum(accLo);
    hi = simd8::sum(accHi);
}

FAULTLINE_HOT void nearBounds1(const NearList& list, const Box& box, float a2, float minD2,
                               const SoftenedKernel& soft, bool lower, float& lo, float& hi) {
    nearBoundsBody<1>(list, box, a2, minD2, soft, lower, lo, hi);
}
FAULTLINE_HOT void nearBounds2(const NearList& list, const Box& box, float a2, float minD2,
                               const SoftenedKernel& soft, bool lower, float& lo, float& hi) {
    nearBoundsBody<2>(list, box, a2, minD2, soft, lower, lo, hi);
}

// Figure 4 colour along a row of 8 voxels (z indices k0 .. k0 + 7): per voxel, the sum of the
// colours of the spheres whose radius + reachAdd holds it, and their number.
FAULTLINE_HOT void colorRow(float x, float y, int k0, float h, const NearList& list, float reachAdd,
                            float red[8], float green[8], float blue[8], float count[8]) {
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

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] Evaluating blocks
//-----------------------------------------------------------------------------

void MetaballField::evaluateColor(const Coord3& o, Vec3f* color) const {
    thread_local NearList colors;
    const Box box = blockBox(o, m_h);
    colors.clear();
    m_grid.gather(box, maxRadius() + m_params.colorReach, colors, true);
    static_assert(kBlockDim == 8, "colorRow fills rows of 8 voxels");
    if (colors.size() == 0) {
        std::fill(color, color + kBlockVoxels, m_params.initialColor);
        return;
    }
    for (int i = 0; i < kBlockDim; ++i)
        for (int j = 0; j < kBlockDim; ++j) {
            float red[8], green[8], blue[8], n[8];
            colorRow((o[0] + i) * m_h, (o[1] + j) * m_h, o[2], m_h, colors, m_params.colorReach,
                     red, green, blue, n);
            for (int k = 0; k < kBlockDim; ++k)
                color[blockOffset(i, j, k)] =
                    n[k] > 0.0f ? Vec3f{red[k] / n[k], green[k] / n[k], blue[k] / n[k]}
                                : m_params.initialColor;
        }
}

void MetaballField::evaluateBlock(const Coord3& o, float* density, Vec3f* color) const {
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

int MetaballField::evaluateBlockUnlessOneSided(const Coord3& o, float* density, float isoMin,
                                               float isoMax, FieldBounds* bounds) const {
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
    // Float terms, as before, summed in float in 8 lanes: positive terms, a few dozen on a
    // sparse set and at most a few thousand, so within 3e-5 of their sum, inside the slack below.
    float nearLoF = 0.0f, nearHiF = 0.0f;
    (m_kernel.p == 2 ? nearBounds2 : nearBounds1)(block, box, a2, m_kernel.minD2, m_soft0,
                                                  evenOrder, nearLoF, nearHiF);
    const double nearLo = nearLoF, nearHi = nearHiF;
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

void MetaballField::gatherNear(const Coord3& o, NearList& block) const {
    const Box box = blockBox(o, m_h);
    block.clear();
    m_grid.gather(box, m_a0, block, false);
}

void MetaballField::nearValues(const Coord3& o, const NearList& block, float* density) const {
    const float a2 = m_a0 * m_a0;
    const bool compact = m_params.kernel == MetaballKernel::Compact;
    const float invC2 = 1.0f / (m_params.compactReach * m_params.compactReach);
    const Box box = blockBox(o, m_h);
    // Each sphere's gap to the lower and upper half of the block along each axis gives its
    // distance to all eight octants in one pass: a bit per octant within a0 of it, which the
    // octant's sums test (most spheres reach all eight: copying them into eight lists cost more
    // than it saved).
    constexpr int kHalf = kBlockDim / 2;
    thread_local std::vector<unsigned char> reach;
    reach.resize(block.size());
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
        unsigned bits = 0;
        for (int octant = 0; octant < 8; ++octant)
            bits |=
                (gap2[0][octant & 1] + gap2[1][(octant >> 1) & 1] + gap2[2][(octant >> 2) & 1] <=
                 a2)
                << octant;
        reach[q] = static_cast<unsigned char>(bits);
    }
    for (int octant = 0; octant < 8; ++octant) {
        const Coord3 lo{o[0] + (octant & 1) * kHalf, o[1] + ((octant >> 1) & 1) * kHalf,
                        o[2] + ((octant >> 2) & 1) * kHalf};
        const int first[3] = {lo[0], lo[1], lo[2]};
        float sums[64];
        (compact           ? octantNear0
         : m_kernel.p == 2 ? octantNear2
                           : octantNear1)(first, m_h, block, reach.data(), unsigned(octant), invC2,
                                          a2, m_kernel.minD2, m_soft0, sums);
        static_assert(kHalf == 4, "octantNear fills 4^3 voxels");
        for (int i = 0; i < kHalf; ++i)
            for (int l = 0; l < 16; ++l)
                density[blockOffset(lo[0] - o[0] + i, lo[1] - o[1] + l / 4, lo[2] - o[2] + l % 4)] =
                    sums[16 * i + l];
    }
}

namespace {

// Near field and its analytic gradient (Algorithm 1 line 8) at one point.
template <int P>
[[gnu::always_inline]] inline void nearGradientBody(const NearList& list, const Vec3f& p, float a2,
                                                    float minD2, float invC2,
                                                    const SoftenedKernel& soft, float out[4]) {
    const std::size_t count = list.size();
    const float* lx = list.x.data();
    const float* ly = list.y.data();
    const float* lz = list.z.data();
    const float* lr = list.r.data();
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

FAULTLINE_HOT void nearGradient0(const NearList& list, const Vec3f& p, float a2, float minD2,
                                 float invC2, const SoftenedKernel& soft, float out[4]) {
    nearGradientBody<0>(list, p, a2, minD2, invC2, soft, out);
}
FAULTLINE_HOT void nearGradient1(const NearList& list, const Vec3f& p, float a2, float minD2,
                                 float invC2, const SoftenedKernel& soft, float out[4]) {
    nearGradientBody<1>(list, p, a2, minD2, invC2, soft, out);
}
FAULTLINE_HOT void nearGradient2(const NearList& list, const Vec3f& p, float a2, float minD2,
                                 float invC2, const SoftenedKernel& soft, float out[4]) {
    nearGradientBody<2>(list, p, a2, minD2, invC2, soft, out);
}

} // namespace

void MetaballField::sumNear(const NearList& list, const Vec3f& p, float& value, Vec3f* gradient,
                            Vec3f* color) const {
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

void MetaballField::evaluatePoints(std::span<const Vec3f> points, float* values,
                                   Vec3f* gradients) const {
    // Group the points by a prepared block next to them: one neighbour list and one coarse
    // patch per group.
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> groups;
    std::vector<std::uint32_t> orphans;
    for (std::size_t n = 0; n < points.size(); ++n) {
        const auto& p = points[n];
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
    std::vector<const std::vector<std::uint32_t>*> groupList;
    std::vector<std::uint32_t> groupBlock;
    for (const auto& [block, members] : groups) {
        groupList.push_back(&members);
        groupBlock.push_back(block);
    }
    tbb::parallel_for(std::size_t{0}, groupList.size(), [&](std::size_t g) {
        const auto& members = *groupList[g];
        const Coord3 origin = m_blockOrigins[groupBlock[g]];
        thread_local NearList list;
        list.clear();
        const Box box = voxelBox({origin[0] - 1, origin[1] - 1, origin[2] - 1},
                                 {origin[0] + 8, origin[1] + 8, origin[2] + 8}, m_h);
        m_tree.gather(box, m_a0, list, false);
        thread_local std::vector<float> patch;
        detail::Int3 s0{0, 0, 0}, sd{0, 0, 0};
        const FieldLevel* level1 = m_levels.empty() ? nullptr : m_levels.front().get();
        if (level1) {
            for (int k = 0; k < 3; ++k) {
                s0[k] = floorDiv(origin[k] - 1, m_ratio1) - detail::kTapsBelow;
                sd[k] = floorDiv(origin[k] + 8, m_ratio1) + detail::kTapsAbove - s0[k] + 1;
            }
            detail::gatherPatch(*level1, s0, sd, patch);
        }
        for (std::uint32_t n : members) {
            const Vec3f& p = points[n];
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
                        const float* row =
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
    const auto& s = m_tree.spheres();
    for (std::uint32_t n : orphans) {
        const Vec3f& p = points[n];
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
