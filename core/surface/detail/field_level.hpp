// FieldLevel: one coarse grid of the multilevel sum, stored as sparse 8^3 bricks of nodes with a
// mask of the nodes some finer level needs. Also the degree-5 (6-tap Lagrange) interpolation
// between levels.
#pragma once

#include "core/surface/metaball_kernel.hpp"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace faultline::core::detail {

using Int3 = std::array<int, 3>;

inline int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Packs a coordinate with each component in [-2^20, 2^20) into a key.
inline std::uint64_t packKey(const Int3& c) {
    constexpr int kBias = 1 << 20;
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[0] + kBias)) << 42) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[1] + kBias)) << 21) |
           static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[2] + kBias));
}

struct Brick {
    Int3 origin{0, 0, 0}; // node index of local (0, 0, 0); multiple of 8
    std::uint64_t mask[8] = {};
    Int3 lo{8, 8, 8}, hi{-1, -1, -1}; // bounding box of the needed nodes, local
    std::array<float, 512> values{};

    static int offset(int i, int j, int k) { return (i * 8 + j) * 8 + k; }
    bool needed(int n) const { return (mask[n >> 6] >> (n & 63)) & 1u; }
};

struct FieldLevel {
    float spacing = 1.0f; // world units between nodes
    int ratio = 2;        // this level's spacing over the finer level's
    float cutoff = 0.0f;  // a_l: this level sums gamma_{a_{l-1}} - gamma_{a_l} within a_l
    SoftenedKernel below; // gamma_{a_{l-1}}
    SoftenedKernel own;   // gamma_{a_l}
    bool top = false;     // the coarsest level sums gamma_{a_{l-1}} over all spheres
    std::unordered_map<std::uint64_t, std::uint32_t> index; // brick coordinate -> brick
    std::vector<Brick> bricks;

    // Marks nodes [lo, hi] (inclusive) as needed.
    void mark(const Int3& lo, const Int3& hi);
    const Brick* find(const Int3& node) const;
    std::size_t neededCount() const;
};

// Interpolation between levels: Lagrange polynomials on kTaps nodes per axis, base - kTapsBelow
// .. base + kTaps - kTapsBelow - 1 around a point in [base, base + 1). Degree 5 keeps the error
// of the smooth remainders small at a coarse spacing of a third of the cutoff.
inline constexpr int kTaps = 6;
inline constexpr int kTapsBelow = 2;
inline constexpr int kTapsAbove = kTaps - kTapsBelow - 1;
void lagrangeWeights(float t, float w[kTaps]);
void lagrangeDerivatives(float t, float w[kTaps]);

// Copies the nodes [lo, lo + dims) of a level into `out` (x slowest, z fastest), rows along z
// strideZ apart (0: dims[2]), zeros past their end.
void gatherPatch(const FieldLevel& level, const Int3& lo, const Int3& dims, std::vector<float>& out,
                 int strideZ = 0);

// Adds to `out` (dims n, z fastest) the degree-5 (kTaps) interpolation of `level` at the finer
// indices [t0, t0 + n), where a finer index t sits at level index t / ratio.
void addInterpolated(const FieldLevel& level, int ratio, const Int3& t0, const Int3& n, float* out);

} // namespace faultline::core::detail
