// Packing the lanes of an eight-wide comparison to the front, without a branch per lane: for
// each 8-bit mask (bit b: lane b kept), the kept lanes' numbers in order, then zeros. A loop
// that tests eight candidates at a time permutes (or offsets) by the row of its mask and
// advances by the mask's popcount, so the kept candidates come out in their order.
#pragma once

#include <cstdint>

namespace faultline::core::detail {

struct LaneTable {
    alignas(32) std::uint32_t lanes[256][8];
};

constexpr LaneTable makeLaneTable() {
    LaneTable t{};
    for (unsigned m = 0; m < 256; ++m) {
        unsigned n = 0;
        for (unsigned b = 0; b < 8; ++b)
            if ((m >> b) & 1u)
                t.lanes[m][n++] = b;
    }
    return t;
}

inline constexpr LaneTable kLaneTable = makeLaneTable();

} // namespace faultline::core::detail
