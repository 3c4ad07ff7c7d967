// Eight floats at a time with GCC vector extensions: the hot field loops are written once and
// compiled for AVX2 + FMA (one register) and for the baseline (two SSE registers) by target_clones.
// Explicit accumulators keep the sums in registers, which the auto-vectoriser did not.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>

// A hot function compiled for x86-64-v3 too (AVX2 with FMA: "avx2" alone leaves every a * b + c
// as two instructions), the variant picked at run time by CPU feature; and for x86-64-v4
// (AVX-512): the same 8-wide code, but with 32 vector registers the window sums' sixteen kernel
// coefficients and accumulators no longer spill to the stack (bench_surface's dense zones at
// r/2, inverse-square: coarse levels 6 % and the whole build 2 % faster on an Ice Lake Xeon).
// clang (the sanitizer build) does not keep the 8-wide helpers' vectors in one ABI across the
// clones and computes garbage: it builds the baseline only (speed does not matter there).
#if defined(__clang__)
#define FAULTLINE_HOT
#else
#define FAULTLINE_HOT __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif

// Vectors are passed only between always-inlined functions: no ABI is involved.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace faultline::core::detail::simd8 {

typedef float v8f __attribute__((vector_size(32)));

typedef int v8i __attribute__((vector_size(32)));

// x in every lane. Written as a shuffle of lane 0: GCC 12 lowers the eight-element initialiser
// before inlining, so inside a target_clones function it became four inserts and a 128-bit
// insert per splat (the near sums splat per sphere) instead of one vbroadcastss.
// (clang, which builds only the baseline, has no __builtin_shuffle.)
[[gnu::always_inline]] inline v8f splat(float x) {
#if defined(__clang__)
    return v8f{x, x, x, x, x, x, x, x};
#else
    return __builtin_shuffle(v8f{x}, v8i{});
#endif
}

[[gnu::always_inline]] inline v8f load(const float* p) {
    v8f v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

[[gnu::always_inline]] inline void store(float* p, v8f v) { std::memcpy(p, &v, sizeof v); }

// The first n (< 8) floats of p, zeros after them.
[[gnu::always_inline]] inline v8f loadPartial(const float* p, std::size_t n) {
    v8f v{};
    for (std::size_t l = 0; l < n; ++l)
        v[l] = p[l];
    return v;
}

// The first min(n, 8) floats of p, zeros after them.
[[gnu::always_inline]] inline v8f loadUpTo(const float* p, std::size_t n) {
    return n >= 8 ? load(p) : loadPartial(p, n);
}

[[gnu::always_inline]] inline v8f max(v8f a, v8f b) { return a < b ? b : a; }

[[gnu::always_inline]] inline v8f inverseSqrt(v8f x) {
    v8f r;
    for (int l = 0; l < 8; ++l)
        r[l] = 1.0f / std::sqrt(x[l]);
    return r;
}

[[gnu::always_inline]] inline float sum(v8f v) {
    return ((v[0] + v[4]) + (v[1] + v[5])) + ((v[2] + v[6]) + (v[3] + v[7]));
}

} // namespace faultline::core::detail::simd8
