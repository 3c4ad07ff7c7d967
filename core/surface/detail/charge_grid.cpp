#include "core/surface/detail/charge_grid.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace faultline::core::detail {

void ChargeGrid::gather(const Int3& first, int size, float cutoff, WindowList& out) const {
    out.clear();
    int from[3], to[3];
    for (int k = 0; k < 3; ++k) {
        const float reach = std::min(cutoff / spacing, float(dims[k]));
        from[k] = std::max(first[k] - static_cast<int>(std::ceil(reach)), lo[k]) - lo[k];
        to[k] = std::min(first[k] + size - 1 + static_cast<int>(std::ceil(reach)),
                         lo[k] + dims[k] - 1) -
                lo[k];
    }
    // A node's distance to the nodes' box along one axis, squared, world.
    auto gap2 = [&](int k, int local) {
        const int node = lo[k] + local;
        const int gap = std::max({first[k] - node, node - (first[k] + size - 1), 0});
        const float d = static_cast<float>(gap) * spacing;
        return d * d;
    };
    const float a2 = cutoff * cutoff;
    for (int a = from[0]; a <= to[0]; ++a) {
        const float da = gap2(0, a);
        if (da >= a2)
            continue;
        for (int b = from[1]; b <= to[1]; ++b) {
            const float dab = da + gap2(1, b);
            if (dab >= a2)
                continue;
            for (int c = from[2]; c <= to[2]; ++c) {
                const float charge = at(a, b, c);
                if (charge != 0.0f && dab + gap2(2, c) < a2)
                    out.push(float(lo[0] + a) * spacing, float(lo[1] + b) * spacing,
                             float(lo[2] + c) * spacing, charge);
            }
        }
    }
    out.pad();
}

namespace {

// Up to this size each of a few chunks of the spheres spreads into a grid of its own, summed
// after; larger grids are spread in place, by slabs of x rows that no two threads write at once.
// Either way in a fixed order: the same charges on every run.
constexpr std::size_t kPrivateChargeNodes = std::size_t{1} << 18;

} // namespace

std::optional<ChargeGrid> anterpolate(const PackedSpheres& s, const Box& centres, float spacing) {
    ChargeGrid g;
    std::size_t total = 1;
    for (int k = 0; k < 3; ++k) {
        const double lo = std::floor(centres.lo[k] / spacing) - kTapsBelow;
        const double hi = std::floor(centres.hi[k] / spacing) + kTapsAbove;
        if (hi - lo + 1 > double(kMaxChargeNodes))
            return std::nullopt;
        g.lo[k] = static_cast<int>(lo);
        g.dims[k] = static_cast<int>(hi - lo + 1);
        total *= static_cast<std::size_t>(g.dims[k]);
        if (total > kMaxChargeNodes)
            return std::nullopt;
    }
    // A sphere's first node along axis k (its kTaps nodes follow).
    auto base = [&](float c, int k) {
        return std::clamp(static_cast<int>(std::floor(c / spacing)) - kTapsBelow - g.lo[k], 0,
                          g.dims[k] - kTaps);
    };
    auto spread = [&](std::size_t i, std::vector<float>& q) {
        float w[3][kTaps];
        int b[3];
        const float c[3] = {s.x[i], s.y[i], s.z[i]};
        for (int k = 0; k < 3; ++k) {
            const float u = c[k] / spacing;
            b[k] = base(c[k], k);
            lagrangeWeights(u - std::floor(u), w[k]);
        }
        for (int a = 0; a < kTaps; ++a)
            for (int e = 0; e < kTaps; ++e) {
                const float wae = s.r[i] * w[0][a] * w[1][e];
                float* row =
                    &q[(static_cast<std::size_t>(b[0] + a) * g.dims[1] + b[1] + e) * g.dims[2] +
                       b[2]];
                for (int f = 0; f < kTaps; ++f)
                    row[f] += wae * w[2][f];
            }
    };
    if (total <= kPrivateChargeNodes) {
        // A fixed number of chunks, summed in order: the same charges on every run.
        constexpr std::size_t kChunks = 8;
        std::vector<std::vector<float>> local(kChunks);
        tbb::parallel_for(std::size_t{0}, kChunks, [&](std::size_t c) {
            local[c].assign(total, 0.0f);
            for (std::size_t i = c * s.size() / kChunks; i < (c + 1) * s.size() / kChunks; ++i)
                spread(i, local[c]);
        });
        g.q.assign(total, 0.0f);
        for (const auto& q : local)
            for (std::size_t n = 0; n < total; ++n)
                g.q[n] += q[n];
    } else {
        // Spheres bucketed by the slab of their first x node; a slab's spheres write its rows and
        // the kTaps - 1 after it, so slabs at least kTaps wide two apart never share a row:
        // the even slabs in parallel, then the odd ones.
        g.q.assign(total, 0.0f);
        const int width = std::max(kTaps, (g.dims[0] + 63) / 64);
        const int slabs = (g.dims[0] + width - 1) / width;
        std::vector<std::uint32_t> start(static_cast<std::size_t>(slabs) + 1, 0), order(s.size());
        for (std::size_t i = 0; i < s.size(); ++i)
            ++start[base(s.x[i], 0) / width + 1];
        for (int k = 0; k < slabs; ++k)
            start[k + 1] += start[k];
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < s.size(); ++i)
            order[fill[base(s.x[i], 0) / width]++] = static_cast<std::uint32_t>(i);
        for (int parity = 0; parity < 2; ++parity)
            tbb::parallel_for(0, (slabs + 1 - parity) / 2, [&](int half) {
                const int slab = 2 * half + parity;
                for (std::uint32_t n = start[slab]; n < start[slab + 1]; ++n)
                    spread(order[n], g.q);
            });
    }
    g.spacing = spacing;
    g.nonzero = static_cast<std::size_t>(
        std::count_if(g.q.begin(), g.q.end(), [](float q) { return q != 0.0f; }));
    return g;
}

} // namespace faultline::core::detail
