#include "core/surface/detail/field_level.hpp"

#include "core/util/simd8.hpp"

#include <algorithm>
#include <cassert>

namespace faultline::core::detail {

void FieldLevel::mark(const Int3& lo, const Int3& hi) {
    Int3 blo, bhi;
    for (int k = 0; k < 3; ++k) {
        blo[k] = floorDiv(lo[k], 8);
        bhi[k] = floorDiv(hi[k], 8);
    }
    for (int bx = blo[0]; bx <= bhi[0]; ++bx)
        for (int by = blo[1]; by <= bhi[1]; ++by)
            for (int bz = blo[2]; bz <= bhi[2]; ++bz) {
                const Int3 b{bx, by, bz};
                auto [it, inserted] =
                    index.try_emplace(packKey(b), static_cast<std::uint32_t>(bricks.size()));
                if (inserted) {
                    bricks.emplace_back();
                    bricks.back().origin = {bx * 8, by * 8, bz * 8};
                }
                Brick& brick = bricks[it->second];
                Int3 l, h;
                for (int k = 0; k < 3; ++k) {
                    l[k] = std::max(lo[k] - brick.origin[k], 0);
                    h[k] = std::min(hi[k] - brick.origin[k], 7);
                    brick.lo[k] = std::min(brick.lo[k], l[k]);
                    brick.hi[k] = std::max(brick.hi[k], h[k]);
                }
                // mask[i] holds the 8 x 8 (j, z) nodes of plane i, a byte per row of z.
                const std::uint64_t row = ((std::uint64_t{1} << (h[2] - l[2] + 1)) - 1) << l[2];
                std::uint64_t plane = 0;
                for (int j = l[1]; j <= h[1]; ++j)
                    plane |= row << (8 * j);
                for (int i = l[0]; i <= h[0]; ++i)
                    brick.mask[i] |= plane;
            }
}

const Brick* FieldLevel::find(const Int3& node) const {
    const Int3 b{floorDiv(node[0], 8), floorDiv(node[1], 8), floorDiv(node[2], 8)};
    auto it = index.find(packKey(b));
    return it == index.end() ? nullptr : &bricks[it->second];
}

std::size_t FieldLevel::neededCount() const {
    std::size_t count = 0;
    for (const auto& b : bricks)
        for (auto m : b.mask)
            count += static_cast<std::size_t>(__builtin_popcountll(m));
    return count;
}

namespace {
// 1 / prod_{j != k} (k - j) for nodes -kTapsBelow .. kTapsAbove.
struct LagrangeDenominators {
    float inv[kTaps];
    LagrangeDenominators() {
        for (int k = 0; k < kTaps; ++k) {
            double d = 1.0;
            for (int j = 0; j < kTaps; ++j)
                if (j != k)
                    d *= double(k - j);
            inv[k] = static_cast<float>(1.0 / d);
        }
    }
};
const LagrangeDenominators kDenominators;
} // namespace

void lagrangeWeights(float t, float w[kTaps]) {
    float x[kTaps];
    for (int j = 0; j < kTaps; ++j)
        x[j] = t - static_cast<float>(j - kTapsBelow);
    // Prefix and suffix products: w_k = prod_{j<k} x_j * prod_{j>k} x_j / denominator_k.
    float prefix[kTaps + 1], suffix[kTaps + 1];
    prefix[0] = 1.0f;
    suffix[kTaps] = 1.0f;
    for (int j = 0; j < kTaps; ++j)
        prefix[j + 1] = prefix[j] * x[j];
    for (int j = kTaps - 1; j >= 0; --j)
        suffix[j] = suffix[j + 1] * x[j];
    for (int k = 0; k < kTaps; ++k)
        w[k] = prefix[k] * suffix[k + 1] * kDenominators.inv[k];
}

void lagrangeDerivatives(float t, float w[kTaps]) {
    float x[kTaps];
    for (int j = 0; j < kTaps; ++j)
        x[j] = t - static_cast<float>(j - kTapsBelow);
    for (int k = 0; k < kTaps; ++k) {
        float sum = 0.0f;
        for (int m = 0; m < kTaps; ++m) {
            if (m == k)
                continue;
            float v = 1.0f;
            for (int j = 0; j < kTaps; ++j)
                if (j != k && j != m)
                    v *= x[j];
            sum += v;
        }
        w[k] = sum * kDenominators.inv[k];
    }
}

void gatherPatch(const FieldLevel& level, const Int3& lo, const Int3& dims, std::vector<float>& out,
                 int strideZ) {
    const std::size_t stride = strideZ > 0 ? strideZ : dims[2];
    assert(stride >= static_cast<std::size_t>(dims[2]));
    out.assign(static_cast<std::size_t>(dims[0]) * dims[1] * stride, 0.0f);
    const Int3 hi{lo[0] + dims[0] - 1, lo[1] + dims[1] - 1, lo[2] + dims[2] - 1};
    for (int bx = floorDiv(lo[0], 8); bx <= floorDiv(hi[0], 8); ++bx)
        for (int by = floorDiv(lo[1], 8); by <= floorDiv(hi[1], 8); ++by)
            for (int bz = floorDiv(lo[2], 8); bz <= floorDiv(hi[2], 8); ++bz) {
                const Brick* brick = level.find({bx * 8, by * 8, bz * 8});
                assert(brick && "a coarse node the interpolation needs was never marked");
                if (!brick)
                    continue;
                const Int3& o = brick->origin;
                Int3 l, h;
                for (int k = 0; k < 3; ++k) {
                    l[k] = std::max(lo[k], o[k]);
                    h[k] = std::min(hi[k], o[k] + 7);
                }
                // Rows along z, copied whole: every node of them was marked as needed.
                const int run = h[2] - l[2] + 1;
                [[maybe_unused]] const unsigned runBits = ((1u << run) - 1u) << (l[2] - o[2]);
                for (int i = l[0]; i <= h[0]; ++i)
                    for (int j = l[1]; j <= h[1]; ++j) {
                        const int n = Brick::offset(i - o[0], j - o[1], l[2] - o[2]);
                        assert(((brick->mask[i - o[0]] >> (8 * (j - o[1]))) & runBits) == runBits &&
                               "a coarse node the interpolation needs was never marked");
                        std::copy_n(
                            &brick->values[n], run,
                            &out[(static_cast<std::size_t>(i - lo[0]) * dims[1] + (j - lo[1])) *
                                     stride +
                                 (l[2] - lo[2])]);
                    }
            }
}

namespace {
// Interpolation weights of the `ratio` finer indices between two nodes (phase g mod ratio),
// computed once per ratio and thread.
const std::array<float, kTaps>* phaseWeights(int ratio) {
    thread_local int cached = 0;
    thread_local std::vector<std::array<float, kTaps>> table;
    if (cached != ratio) {
        table.resize(static_cast<std::size_t>(ratio));
        for (int p = 0; p < ratio; ++p)
            lagrangeWeights(static_cast<float>(p) / static_cast<float>(ratio), table[p].data());
        cached = ratio;
    }
    return table.data();
}

// The three separable passes over a patch whose rows along z are a whole number of 8-lane
// vectors (zeros past their end): x, then y on whole rows, then z as an 8 x stride matrix of
// weights applied to each row. Up to 8 targets along z.
FAULTLINE_HOT void interpolatePasses(const float* src, const Int3& sd, int stride, const Int3& n,
                                     const int* const base[3], const float* const* const weights[3],
                                     const float* zMatrix, float* pass1, float* pass2, float* out) {
    using simd8::v8f;
    const int vectors = stride / 8;
    // x pass: [n0][sd1][stride], each vector of a plane summed in a register.
    const std::size_t plane = static_cast<std::size_t>(sd[1]) * stride;
    for (int i = 0; i < n[0]; ++i) {
        float* d = pass1 + i * plane;
        v8f w[kTaps];
#if defined(__GNUC__) && !defined(__clang__) // GCC 12 takes these stores for uses of w[4], w[5]
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
        for (int q = 0; q < kTaps; ++q)
            w[q] = simd8::splat(weights[0][i][q]);
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
        const float* s = src + base[0][i] * plane;
        for (std::size_t e = 0; e < plane; e += 8) {
            v8f acc{};
            for (int q = 0; q < kTaps; ++q)
                acc += w[q] * simd8::load(s + q * plane + e);
            simd8::store(d + e, acc);
        }
    }
    // y pass: [n0][n1][stride]
    for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j) {
            for (int v = 0; v < vectors; ++v) {
                v8f acc{};
                for (int q = 0; q < kTaps; ++q)
                    acc += simd8::splat(weights[1][j][q]) *
                           simd8::load(pass1 + (i * sd[1] + base[1][j] + q) * stride + 8 * v);
                simd8::store(pass2 + (static_cast<std::size_t>(i) * n[1] + j) * stride + 8 * v,
                             acc);
            }
        }
    // z pass: each row times the weights matrix (column e: what source e gives each target).
    for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j) {
            const float* s = pass2 + (static_cast<std::size_t>(i) * n[1] + j) * stride;
            v8f acc{};
            for (int e = 0; e < sd[2]; ++e)
                acc += simd8::splat(s[e]) * simd8::load(zMatrix + 8 * e);
            float* d = out + (static_cast<std::size_t>(i) * n[1] + j) * n[2];
            if (n[2] == 8) {
                simd8::store(d, simd8::load(d) + acc);
            } else {
                for (int z = 0; z < n[2]; ++z)
                    d[z] += acc[z];
            }
        }
}
} // namespace

void addInterpolated(const FieldLevel& level, int ratio, const Int3& t0, const Int3& n,
                     float* out) {
    Int3 s0, sd;
    for (int k = 0; k < 3; ++k) {
        s0[k] = floorDiv(t0[k], ratio) - kTapsBelow;
        sd[k] = floorDiv(t0[k] + n[k] - 1, ratio) + kTapsAbove - s0[k] + 1;
    }
    assert(n[2] <= 8 && "the z pass fills up to 8 targets");
    const int stride = (sd[2] + 7) / 8 * 8;
    thread_local std::vector<float> src, pass1, pass2, zMatrix;
    thread_local std::vector<int> base[3];
    thread_local std::vector<const float*> weights[3];
    gatherPatch(level, s0, sd, src, stride);
    // Per target index along each axis: first source node and weights.
    const std::array<float, kTaps>* phases = phaseWeights(ratio);
    for (int k = 0; k < 3; ++k) {
        base[k].resize(n[k]);
        weights[k].resize(n[k]);
        for (int t = 0; t < n[k]; ++t) {
            const int g = t0[k] + t;
            const int b = floorDiv(g, ratio);
            base[k][t] = b - kTapsBelow - s0[k];
            weights[k][t] = phases[g - b * ratio].data();
        }
    }
    zMatrix.assign(static_cast<std::size_t>(sd[2]) * 8, 0.0f);
    for (int z = 0; z < n[2]; ++z)
        for (int q = 0; q < kTaps; ++q)
            zMatrix[(base[2][z] + q) * 8 + z] = weights[2][z][q];
    pass1.resize(static_cast<std::size_t>(n[0]) * sd[1] * stride);
    pass2.resize(static_cast<std::size_t>(n[0]) * n[1] * stride);
    const int* const bases[3] = {base[0].data(), base[1].data(), base[2].data()};
    const float* const* const ws[3] = {weights[0].data(), weights[1].data(), weights[2].data()};
    interpolatePasses(src.data(), sd, stride, n, bases, ws, zMatrix.data(), pass1.data(),
                      pass2.data(), out);
}

} // namespace faultline::core::detail
