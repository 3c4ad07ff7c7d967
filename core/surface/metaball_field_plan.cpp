// MetaballField, planning (see metaball_field.cpp for the algorithm): guaranteed bounds of the
// field over boxes, by direct sums 8 spheres at a time or the sphere tree, and the coarse levels'
// nodes the planned blocks need.

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

} // namespace

void detail::addDirectBounds(int power, const float* x, const float* y, const float* z,
                             const float* r, std::size_t count, const Box& box, float minD2,
                             double& low, double& high) {
    double lo = 0.0, hi = 0.0;
    (power == 1 ? directBounds1 : directBounds2)(x, y, z, r, count, box, minD2, 0.0f, lo, hi);
    // Float sums of positive terms, count / 8 per lane: each within that many roundings
    // (6e-8 each) of the exact sum; widened by twice that (and at least 1e-4) they stay bounds.
    const double widen = std::max(1e-4, 2.0 * 6e-8 * double(count / 8 + 8));
    low += lo * (1.0 - widen);
    high += hi * (1.0 + widen);
}

double MetaballField::weightWithin(const Vec3f& p, double a) const {
    const Box point{{p[0], p[1], p[2]}, {p[0], p[1], p[2]}};
    const float a2 = static_cast<float>(a * a);
    const auto& nodes = m_tree.nodes();
    const auto& s = m_tree.spheres();
    if (s.size() <= kDirectBoundsSpheres)
        return directWeightWithin(s.x.data(), s.y.data(), s.z.data(), s.r.data(), s.size(), p, a2);
    double sum = 0.0;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const auto& node = nodes[stack[--top]];
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

//-----------------------------------------------------------------------------
// [SECTION] Bounds over boxes
//-----------------------------------------------------------------------------

FieldBounds MetaballField::bounds(const Coord3& lo, const Coord3& hi, double isoMin, double isoMax,
                                  int maxOpen) const {
    const Box box = voxelBox(lo, hi, m_h);
    const BoundKernel k{m_params.kernel, m_kernel, m_params.compactReach};
    const auto& nodes = m_tree.nodes();
    const auto& s = m_tree.spheres();
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
        bool operator<(const Item& o) const { return gap < o.gap; }
    };
    auto itemFor = [&](std::int32_t index) {
        const auto& node = nodes[index];
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
        const auto& node = nodes[item.node];
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
        for (const auto& o : blocks) {
            detail::Int3 lo, hi;
            for (int k = 0; k < 3; ++k) {
                lo[k] = floorDiv(o[k] - 1, m_ratio1) - detail::kTapsBelow;
                hi[k] = floorDiv(o[k] + kBlockDim, m_ratio1) + detail::kTapsAbove;
            }
            level1->mark(lo, hi);
        }
        m_span2 = 0.0;
        const auto& cb = centreBox();
        for (int k = 0; k < 3; ++k) {
            double lo = cb.lo[k], hi = cb.hi[k];
            for (const auto& b : level1->bricks) {
                lo = std::min(lo, double(b.origin[k] + b.lo[k]) * level1->spacing);
                hi = std::max(hi, double(b.origin[k] + b.hi[k]) * level1->spacing);
            }
            m_span2 += (hi - lo) * (hi - lo);
        }
        m_levels.push_back(std::move(level1));
    }
    // Levels above the last choice's top wait in m_spareLevels.
    for (auto& spare : m_spareLevels)
        m_levels.push_back(std::move(spare));
    m_spareLevels.clear();
    for (auto& level : m_levels)
        level->top = false;
    const double n = static_cast<double>(sphereCount());
    const double span2 = m_span2;
    for (int l = 1;; ++l) {
        FieldLevel& level = *m_levels[l - 1];
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
                const Brick& b = level.bricks[bi];
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
        for (const auto& b : level.bricks) {
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

} // namespace faultline::core
