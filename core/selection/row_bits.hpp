// Row bits: one 64-bit word per 64 rows (bit j = row 64w + j) for the visibility tests, with
// SSE2 paths and scalar references (the scalar code is the specification; tests compare both).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#define FAULTLINE_ROW_BITS_SSE2 1
#endif

namespace faultline::core::detail {

inline constexpr std::size_t kWordRows = 64;

inline std::size_t wordCount(std::size_t rows) { return (rows + kWordRows - 1) / kWordRows; }
// The bits of the first `count` rows of a word (count <= 64).
inline std::uint64_t lowBits(std::size_t count) {
    return count >= kWordRows ? ~std::uint64_t{0} : (std::uint64_t{1} << count) - 1;
}

// A bound typed by the user (double) as the float the values are stored in: rounded to the
// nearest float, as the reader rounded the values. Rounding is monotonic, so every value that
// lies within the bounds in the file still does, and a value printed as exactly the bound
// (radius 0.005 against a threshold at 0.005) passes, as a check on the file's decimals says.
// Only values within one float step of a bound can be taken as equal to it.
// NaN stays NaN (every comparison then fails); a finite bound beyond the float range becomes
// the largest float (an infinite value still fails it), an infinite bound stays infinite.
inline float nearestFloatBound(double d) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (std::isnan(d))
        return std::numeric_limits<float>::quiet_NaN();
    if (std::isinf(d))
        return d > 0 ? std::numeric_limits<float>::infinity()
                     : -std::numeric_limits<float>::infinity();
    if (d > kMax)
        return std::numeric_limits<float>::max();
    if (d < -kMax)
        return -std::numeric_limits<float>::max();
    return static_cast<float>(d);
}

// Integer bounds equivalent to lo <= v <= hi for every int32 v; empty when no int32 passes.
struct IntBounds {
    std::int32_t lo = 0;
    std::int32_t hi = -1;
    bool empty() const { return lo > hi; }
};
inline IntBounds intBoundsFor(double lo, double hi) {
    constexpr double kMin = std::numeric_limits<std::int32_t>::min();
    constexpr double kMax = std::numeric_limits<std::int32_t>::max();
    const double l = std::ceil(lo);
    const double h = std::floor(hi);
    if (std::isnan(l) || std::isnan(h) || l > kMax || h < kMin || l > h)
        return {};
    return {static_cast<std::int32_t>(l < kMin ? kMin : l),
            static_cast<std::int32_t>(h > kMax ? kMax : h)};
}

// An axis-aligned box as float bounds (rounded with nearestFloatBound).
struct FloatBox {
    std::array<float, 3> min{};
    std::array<float, 3> max{};
    bool operator==(const FloatBox&) const = default;
};

namespace scalar {

inline std::uint64_t inRangeWord(const float* v, std::size_t count, float lo, float hi) {
    std::uint64_t bits = 0;
    for (std::size_t j = 0; j < count; ++j)
        bits |= std::uint64_t{v[j] >= lo && v[j] <= hi} << j;
    return bits;
}
inline std::uint64_t inRangeWord(const std::int32_t* v, std::size_t count, std::int32_t lo,
                                 std::int32_t hi) {
    std::uint64_t bits = 0;
    for (std::size_t j = 0; j < count; ++j)
        bits |= std::uint64_t{v[j] >= lo && v[j] <= hi} << j;
    return bits;
}
inline std::uint64_t inBoxWord(const float* x, const float* y, const float* z, std::size_t count,
                               const FloatBox& b) {
    std::uint64_t bits = 0;
    for (std::size_t j = 0; j < count; ++j)
        bits |= std::uint64_t{x[j] >= b.min[0] && x[j] <= b.max[0] && y[j] >= b.min[1] &&
                              y[j] <= b.max[1] && z[j] >= b.min[2] && z[j] <= b.max[2]}
                << j;
    return bits;
}
inline std::uint64_t nonZeroWord(const std::uint8_t* bytes, std::size_t count) {
    std::uint64_t bits = 0;
    for (std::size_t j = 0; j < count; ++j)
        bits |= std::uint64_t{bytes[j] != 0} << j;
    return bits;
}
inline void expandWord(std::uint64_t bits, std::uint8_t* out, std::size_t count) {
    for (std::size_t j = 0; j < count; ++j)
        out[j] = static_cast<std::uint8_t>((bits >> j) & 1u);
}

} // namespace scalar

#if FAULTLINE_ROW_BITS_SSE2
inline std::uint64_t inRangeWord(const float* v, std::size_t count, float lo, float hi) {
    if (count != kWordRows)
        return scalar::inRangeWord(v, count, lo, hi);
    const __m128 l = _mm_set1_ps(lo);
    const __m128 h = _mm_set1_ps(hi);
    std::uint64_t bits = 0;
    for (unsigned j = 0; j < 16; ++j) {
        const __m128 x = _mm_loadu_ps(v + 4 * j);
        const __m128 in = _mm_and_ps(_mm_cmpge_ps(x, l), _mm_cmple_ps(x, h)); // NaN: false
        bits |= static_cast<std::uint64_t>(_mm_movemask_ps(in)) << (4 * j);
    }
    return bits;
}
inline std::uint64_t inRangeWord(const std::int32_t* v, std::size_t count, std::int32_t lo,
                                 std::int32_t hi) {
    if (count != kWordRows)
        return scalar::inRangeWord(v, count, lo, hi);
    const __m128i l = _mm_set1_epi32(lo);
    const __m128i h = _mm_set1_epi32(hi);
    std::uint64_t bits = 0;
    for (unsigned j = 0; j < 16; ++j) {
        const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(v + 4 * j));
        const __m128i out = _mm_or_si128(_mm_cmplt_epi32(x, l), _mm_cmpgt_epi32(x, h));
        const unsigned outBits = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(out)));
        bits |= static_cast<std::uint64_t>(~outBits & 0xFu) << (4 * j);
    }
    return bits;
}
inline std::uint64_t inBoxWord(const float* x, const float* y, const float* z, std::size_t count,
                               const FloatBox& b) {
    if (count != kWordRows)
        return scalar::inBoxWord(x, y, z, count, b);
    const __m128 x0 = _mm_set1_ps(b.min[0]), x1 = _mm_set1_ps(b.max[0]);
    const __m128 y0 = _mm_set1_ps(b.min[1]), y1 = _mm_set1_ps(b.max[1]);
    const __m128 z0 = _mm_set1_ps(b.min[2]), z1 = _mm_set1_ps(b.max[2]);
    std::uint64_t bits = 0;
    for (unsigned j = 0; j < 16; ++j) {
        const __m128 px = _mm_loadu_ps(x + 4 * j);
        const __m128 py = _mm_loadu_ps(y + 4 * j);
        const __m128 pz = _mm_loadu_ps(z + 4 * j);
        __m128 in = _mm_and_ps(_mm_cmpge_ps(px, x0), _mm_cmple_ps(px, x1));
        in = _mm_and_ps(in, _mm_and_ps(_mm_cmpge_ps(py, y0), _mm_cmple_ps(py, y1)));
        in = _mm_and_ps(in, _mm_and_ps(_mm_cmpge_ps(pz, z0), _mm_cmple_ps(pz, z1)));
        bits |= static_cast<std::uint64_t>(_mm_movemask_ps(in)) << (4 * j);
    }
    return bits;
}
inline std::uint64_t nonZeroWord(const std::uint8_t* bytes, std::size_t count) {
    if (count != kWordRows)
        return scalar::nonZeroWord(bytes, count);
    const __m128i zero = _mm_setzero_si128();
    std::uint64_t bits = 0;
    for (unsigned j = 0; j < 4; ++j) {
        const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bytes + 16 * j));
        const unsigned zeros = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(b, zero)));
        bits |= static_cast<std::uint64_t>(~zeros & 0xFFFFu) << (16 * j);
    }
    return bits;
}
#else
using scalar::inBoxWord;
using scalar::inRangeWord;
using scalar::nonZeroWord;
#endif

// Byte b -> eight bytes, byte k = bit k of b (little-endian order in memory).
inline constexpr std::array<std::uint64_t, 256> kSpreadBits = [] {
    std::array<std::uint64_t, 256> table{};
    for (unsigned b = 0; b < 256; ++b)
        for (unsigned k = 0; k < 8; ++k)
            if ((b >> k) & 1u)
                table[b] |= std::uint64_t{1} << (8 * k);
    return table;
}();

// Writes one byte (0 or 1) per row.
inline void expandWord(std::uint64_t bits, std::uint8_t* out, std::size_t count) {
    if constexpr (std::endian::native == std::endian::little) {
        if (count == kWordRows) {
            for (unsigned k = 0; k < 8; ++k) {
                const std::uint64_t bytes = kSpreadBits[(bits >> (8 * k)) & 0xFFu];
                std::memcpy(out + 8 * k, &bytes, 8);
            }
            return;
        }
    }
    scalar::expandWord(bits, out, count);
}

} // namespace faultline::core::detail
