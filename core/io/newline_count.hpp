// Counting newlines fast: 16 bytes a step with SSE2 where available. GCC does not vectorise
// std::count at -O2, and line counting is what indexing and parsing a dump spend time on.
#pragma once

#include <cstddef>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace faultline::core {

inline std::size_t countNewlines(const char* p, const char* end) {
    std::size_t count = 0;
#if defined(__SSE2__)
    const __m128i nl = _mm_set1_epi8('\n');
    while (end - p >= 16) {
        const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
        count += static_cast<std::size_t>(
            __builtin_popcount(static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, nl)))));
        p += 16;
    }
#endif
    for (; p < end; ++p)
        count += *p == '\n';
    return count;
}

} // namespace faultline::core
