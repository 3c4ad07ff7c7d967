#include "core/util/points_within.hpp"

#include "core/util/lane_table.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FAULTLINE_WITHIN_AVX2 1
#include <immintrin.h>
#else
#define FAULTLINE_WITHIN_AVX2 0
#endif

namespace faultline::core {

namespace {

std::size_t pointsWithinScalar(const float* __restrict x, const float* __restrict y,
                               const float* __restrict z, std::size_t m, float px, float py,
                               float pz, float r2, float* __restrict d2,
                               std::uint32_t* __restrict within) {
    for (std::size_t t = 0; t < m; ++t) {
        const float dx = px - x[t], dy = py - y[t], dz = pz - z[t];
        d2[t] = dx * dx + dy * dy + dz * dz;
    }
    std::size_t n = 0; // without branches
    for (std::size_t t = 0; t < m; ++t) {
        within[n] = std::uint32_t(t);
        n += d2[t] <= r2;
    }
    return n;
}

#if FAULTLINE_WITHIN_AVX2
__attribute__((target("avx2"))) std::size_t pointsWithinAvx2(const float* x, const float* y,
                                                             const float* z, std::size_t m,
                                                             float px, float py, float pz, float r2,
                                                             float* d2, std::uint32_t* within) {
    const __m256 qx = _mm256_set1_ps(px), qy = _mm256_set1_ps(py), qz = _mm256_set1_ps(pz);
    const __m256 c2 = _mm256_set1_ps(r2);
    std::size_t n = 0;
    for (std::size_t t = 0; t < m; t += 8) {
        const __m256 dx = _mm256_sub_ps(qx, _mm256_loadu_ps(x + t));
        const __m256 dy = _mm256_sub_ps(qy, _mm256_loadu_ps(y + t));
        const __m256 dz = _mm256_sub_ps(qz, _mm256_loadu_ps(z + t));
        // (dx dx + dy dy) + dz dz, each product rounded: the scalar expression's value.
        const __m256 d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                       _mm256_mul_ps(dz, dz));
        _mm256_storeu_ps(d2 + t, d);
        const std::size_t left = m - t;
        const unsigned mask =
            static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d, c2, _CMP_LE_OQ))) &
            (left >= 8 ? 0xffu : (1u << left) - 1u);
        const __m256i lanes =
            _mm256_load_si256(reinterpret_cast<const __m256i*>(detail::kLaneTable.lanes[mask]));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(within + n),
                            _mm256_add_epi32(lanes, _mm256_set1_epi32(static_cast<int>(t))));
        n += static_cast<std::size_t>(__builtin_popcount(mask));
    }
    return n;
}
#endif

} // namespace

std::size_t pointsWithin(const float* x, const float* y, const float* z, std::size_t m, float px,
                         float py, float pz, float r2, float* d2, std::uint32_t* within) {
#if FAULTLINE_WITHIN_AVX2
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2)
        return pointsWithinAvx2(x, y, z, m, px, py, pz, r2, d2, within);
#endif
    return pointsWithinScalar(x, y, z, m, px, py, pz, r2, d2, within);
}

} // namespace faultline::core
