// The points of a small set (a few hundred to a few thousand) within a distance of one point,
// in their order, with every point's squared distance: the inner loop of code that measures
// one sphere against the spheres gathered around its cell.
#pragma once

#include <cstddef>
#include <cstdint>

namespace faultline::core {

// For t < m: d2[t] = (dx * dx + dy * dy) + dz * dz with dx = px - x[t] (and so on), rounded as
// that scalar expression is (no fused multiply-add); the t with d2[t] <= r2 (never a NaN's)
// written to `within` in increasing order. Returns how many. Runs eight points at a time with
// AVX2 where the CPU has it: x, y and z are read, and d2 and `within` written, up to m + 7 (the
// reads past m are left out, so need not be initialised, but must be in the arrays).
std::size_t pointsWithin(const float* x, const float* y, const float* z, std::size_t m, float px,
                         float py, float pz, float r2, float* d2, std::uint32_t* within);

} // namespace faultline::core
