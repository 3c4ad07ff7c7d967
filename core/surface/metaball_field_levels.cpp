// MetaballField, levels (see metaball_field.cpp for the algorithm): prepare() and its steps,
// which compute the coarse levels' values for the planned blocks (window sums, interpolation from
// the level above).

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

// One window term at squared distances d2 (eight at a time), before its weight: gamma_below -
// gamma_own within own's cutoff (a coarse level's window), or gamma_below (top level).
template <int P, bool Top>
[[gnu::always_inline]] inline simd8::v8f windowTerm(const WindowKernels& k, simd8::v8f d2) {
    using simd8::v8f;
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
    return v;
}

// Window sums of NZ nodes of one row along z (at x, y and zs[]), the spheres (or charges) in
// the lanes: the x and y part of each squared distance is formed once for the row's nodes.
template <int P, bool Top, int NZ>
[[gnu::always_inline]] inline void
windowRowBody(float x, float y, const float* zs, const float* px, const float* py, const float* pz,
              const float* pw, std::size_t count, const WindowKernels& k, float* out) {
    using simd8::load;
    using simd8::v8f;
    const v8f vx = simd8::splat(x), vy = simd8::splat(y);
    v8f vz[NZ], acc[NZ];
    for (int n = 0; n < NZ; ++n)
        vz[n] = simd8::splat(zs[n]), acc[n] = v8f{};
    auto add = [&](v8f sx, v8f sy, v8f sz, v8f w) {
        const v8f dx = vx - sx, dy = vy - sy;
        const v8f xy2 = dx * dx + dy * dy;
        for (int n = 0; n < NZ; ++n) {
            const v8f dz = vz[n] - sz;
            acc[n] += w * windowTerm<P, Top>(k, xy2 + dz * dz);
        }
    };
    std::size_t q = 0;
    for (; q + 8 <= count; q += 8)
        add(load(px + q), load(py + q), load(pz + q), load(pw + q));
    if (q < count) {
        // Padding lanes have weight 0 (and a clamped, finite kernel).
        const std::size_t n = count - q;
        add(simd8::loadPartial(px + q, n), simd8::loadPartial(py + q, n),
            simd8::loadPartial(pz + q, n), simd8::loadPartial(pw + q, n));
    }
    for (int n = 0; n < NZ; ++n)
        out[n] = simd8::sum(acc[n]);
}

template <int P, bool Top>
[[gnu::always_inline]] inline void
windowRowDispatch(float x, float y, const float* zs, int nz, const float* px, const float* py,
                  const float* pz, const float* pw, std::size_t count, const WindowKernels& k,
                  float* out) {
    switch (nz) {
    case 1:
        windowRowBody<P, Top, 1>(x, y, zs, px, py, pz, pw, count, k, out);
        break;
    case 2:
        windowRowBody<P, Top, 2>(x, y, zs, px, py, pz, pw, count, k, out);
        break;
    case 3:
        windowRowBody<P, Top, 3>(x, y, zs, px, py, pz, pw, count, k, out);
        break;
    default:
        windowRowBody<P, Top, 4>(x, y, zs, px, py, pz, pw, count, k, out);
        break;
    }
}

// power: the kernel's (1 or 2); top: the top level's sums (no own cutoff).
FAULTLINE_HOT void windowRow(int power, bool top, float x, float y, const float* zs, int nz,
                             const float* px, const float* py, const float* pz, const float* pw,
                             std::size_t count, const WindowKernels& kernels, float* out) {
    if (power == 2 && top)
        windowRowDispatch<2, true>(x, y, zs, nz, px, py, pz, pw, count, kernels, out);
    else if (power == 2)
        windowRowDispatch<2, false>(x, y, zs, nz, px, py, pz, pw, count, kernels, out);
    else if (top)
        windowRowDispatch<1, true>(x, y, zs, nz, px, py, pz, pw, count, kernels, out);
    else
        windowRowDispatch<1, false>(x, y, zs, nz, px, py, pz, pw, count, kernels, out);
}

// Bounds of f over a box from every sphere on its own (no tree): the tightest bounds of their
// kind, and for a few thousand spheres cheaper than opening tree nodes one at a time.
// P: kernel power, 0 for the compact kernel. Sums lo (f at each sphere's farthest point of the
// box) and hi (at its nearest).

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] Preparing the levels for planned blocks
//-----------------------------------------------------------------------------

// prepare(): index the blocks, choose the cutoffs for the levels they need, choose which
// coarse levels sum grid charges, then compute every level's needed nodes from the top down.
void MetaballField::prepare(std::span<const Coord3> blocks, Interrupter* interrupter) {
    indexBlocks(blocks);
    m_levels.clear();
    m_spareLevels.clear();
    m_markedRatio = 0;
    if (m_params.kernel == MetaballKernel::Compact || blocks.empty())
        return;
    chooseCutoffsFor(blocks);
    computeLevels(chooseChargeLevels(), interrupter);
}

void MetaballField::indexBlocks(std::span<const Coord3> blocks) {
    m_blocks.clear();
    m_blockOrigins.assign(blocks.begin(), blocks.end());
    for (std::size_t i = 0; i < blocks.size(); ++i)
        m_blocks.emplace(packKey({floorDiv(blocks[i][0], 8), floorDiv(blocks[i][1], 8),
                                  floorDiv(blocks[i][2], 8)}),
                         static_cast<std::uint32_t>(i));
}

// The constructor's estimate assumed coarse levels up to twice the span; with the levels these
// blocks need (often fewer), a cheaper pair of cutoffs may fit the budget. The cheapest that
// does is the choice (level 1's term alone, a lower bound, skips most without planning). Plans
// the levels (planLevels) for the choice.
void MetaballField::chooseCutoffsFor(std::span<const Coord3> blocks) {
    const CutoffChoice chosen{m_kappa, m_coarseKappa, m_ratio1, m_estimatedError, 0.0};
    const double budget = errorBudget(m_params);
    bool cheaper = false;
    for (const CutoffChoice& c : m_cheaper) {
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
}

// The error of this hierarchy: level 1's interpolation and each coarser level's (the top level's
// values are exact sums, with nothing above to interpolate). Then from the top down, a level
// sums grid charges instead of spheres while that (a second interpolation error of the same
// size, on the spheres' side) fits the budget and the charges are few enough. Returns each
// level's charges (none for the levels that sum spheres).
std::vector<std::optional<ChargeGrid>> MetaballField::chooseChargeLevels() {
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
    return charges;
}

// Computes the nodes the blocks need, from the coarsest level down: each level adds its window
// sums (sumWindows) to the interpolation of the level above.
void MetaballField::computeLevels(const std::vector<std::optional<ChargeGrid>>& charges,
                                  Interrupter* interrupter) {
    // A top level with charges sums all of them: one list for all its nodes.
    WindowList topCharges;
    if (!charges.empty() && charges.back())
        charges.back()->gather(charges.back()->lo, 1, std::numeric_limits<float>::infinity(),
                               topCharges);

    // Compute from the coarsest level down: each level adds its window sum to the degree-5
    // interpolation of the level above.
    std::size_t totalBricks = 0;
    for (const auto& l : m_levels)
        totalBricks += l->bricks.size();
    std::atomic<std::size_t> done{0};
    std::atomic<bool> cancelled{false};
    for (int li = static_cast<int>(m_levels.size()) - 1; li >= 0; --li) {
        FieldLevel& level = *m_levels[li];
        const FieldLevel* above =
            li + 1 < static_cast<int>(m_levels.size()) ? m_levels[li + 1].get() : nullptr;
        tbb::parallel_for(std::size_t{0}, level.bricks.size(), [&](std::size_t bi) {
            if (cancelled.load(std::memory_order_relaxed))
                return;
            Brick& brick = level.bricks[bi];
            sumWindows(level, brick, charges[li] ? &*charges[li] : nullptr, topCharges);
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

// One brick's window sums: each needed node sums the spheres (or charges) within the level's
// cutoff, through the level's window kernels.
void MetaballField::sumWindows(const FieldLevel& level, Brick& brick, const ChargeGrid* grid,
                               const WindowList& topCharges) const {
    const auto& s = m_tree.spheres();
    const WindowKernels kernels(level.below, level.own, m_kernel.minD2);
    const InverseKernel kernel = m_kernel;
    // Nodes in 4^3 groups, each with its own sphere ranges: the window (a ball of radius
    // a_l) fills more of a small group's box than of the whole brick's.
    constexpr int kGroup = 4;
    for (int gi = brick.lo[0] & ~(kGroup - 1); gi <= brick.hi[0]; gi += kGroup)
        for (int gj = brick.lo[1] & ~(kGroup - 1); gj <= brick.hi[1]; gj += kGroup)
            for (int gz = brick.lo[2] & ~(kGroup - 1); gz <= brick.hi[2]; gz += kGroup) {
                int needed[kGroup * kGroup * kGroup], count = 0;
                for (int c = 0; c < kGroup * kGroup * kGroup; ++c) {
                    const int off = Brick::offset(gi + c / (kGroup * kGroup),
                                                  gj + (c / kGroup) % kGroup, gz + c % kGroup);
                    if (brick.needed(off))
                        needed[count++] = off;
                }
                if (count == 0)
                    continue;
                // What every node of the group sums, contiguous: all spheres at the top
                // level (straight from the tree's arrays) or all its charges, else the
                // spheres or charges of the window, gathered once per group and padded.
                const float *px = s.x.data(), *py = s.y.data(), *pz = s.z.data(), *pw = s.r.data();
                std::size_t len = s.size();
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
                        thread_local std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
                        ranges.clear();
                        Box box;
                        for (int k = 0; k < 3; ++k) {
                            box.lo[k] = (brick.origin[k] + g[k]) * level.spacing;
                            box.hi[k] = (brick.origin[k] + g[k] + kGroup - 1) * level.spacing;
                        }
                        m_tree.gatherRanges(box, level.cutoff, ranges);
                        window.clear();
                        for (const auto& range : ranges) {
                            auto copy = [&](const std::vector<float>& from,
                                            std::vector<float>& to) {
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
                // The needed nodes a row along z at a time (they come in blockOffset order:
                // z fastest).
                for (int n = 0; n < count;) {
                    const int row = needed[n] >> 3;
                    int end = n + 1;
                    while (end < count && needed[end] >> 3 == row)
                        ++end;
                    const int i = row >> 3, j = row & 7;
                    float zs[kGroup], sums[kGroup];
                    for (int m = n; m < end; ++m)
                        zs[m - n] = (brick.origin[2] + (needed[m] & 7)) * level.spacing;
                    const float x = (brick.origin[0] + i) * level.spacing;
                    const float y = (brick.origin[1] + j) * level.spacing;
                    windowRow(kernel.p, level.top, x, y, zs, end - n, px, py, pz, pw, len, kernels,
                              sums);
                    for (int m = n; m < end; ++m)
                        brick.values[needed[m]] = sums[m - n];
                    n = end;
                }
            }
}

} // namespace faultline::core
