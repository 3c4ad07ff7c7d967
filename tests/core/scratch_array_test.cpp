// Scratch arrays: large ones are kept once freed and handed out again for the same size, the
// pool never holds more than its cap, and small ones are plain allocations.
#include "core/util/scratch_array.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using namespace faultline::core;

namespace {
constexpr std::size_t kMiB = std::size_t(1) << 20;
}

TEST(ScratchArray, AFreedLargeArrayIsHandedOutAgainForTheSameSize) {
    releaseScratchPool();
    const float* first = nullptr;
    {
        auto a = makeScratchArray<float>(3 * kMiB); // 12 MiB
        first = a.get();
        a[0] = 1.0f;
        a[3 * kMiB - 1] = 2.0f; // the whole request is usable
        EXPECT_EQ(scratchPoolBytes(), 0u);
    }
    EXPECT_EQ(scratchPoolBytes(), 12 * kMiB);
    {
        // Another size does not take it; the same byte count (another type) does.
        auto other = makeScratchArray<float>(5 * kMiB);
        EXPECT_NE(other.get(), first);
        auto same = makeScratchArray<std::uint32_t>(3 * kMiB);
        EXPECT_EQ(static_cast<const void*>(same.get()), static_cast<const void*>(first));
        EXPECT_EQ(scratchPoolBytes(), 0u);
    }
    EXPECT_EQ(scratchPoolBytes(), 32 * kMiB);
    releaseScratchPool();
    EXPECT_EQ(scratchPoolBytes(), 0u);
}

TEST(ScratchArray, ThePoolKeepsTheMostRecentlyFreedWithinItsCap) {
    releaseScratchPool();
    const std::size_t block = kScratchPoolBytes / 4; // four fit exactly
    std::vector<ScratchArray<char>> arrays;
    for (int k = 0; k < 6; ++k)
        arrays.push_back(makeScratchArray<char>(block));
    const char* last = arrays.back().get();
    arrays.clear(); // freed first to last: the first two are let go
    EXPECT_EQ(scratchPoolBytes(), kScratchPoolBytes);
    auto again = makeScratchArray<char>(block);
    EXPECT_EQ(again.get(), last); // the most recently freed of its size
    // Larger than the whole pool, or under a huge page: never kept.
    { auto huge = makeScratchArray<char>(kScratchPoolBytes + 1); }
    { auto small = makeScratchArray<char>(1000); }
    { auto none = makeScratchArray<char>(0); }
    EXPECT_EQ(scratchPoolBytes(), kScratchPoolBytes - block);
    again.reset();
    releaseScratchPool();
    EXPECT_EQ(scratchPoolBytes(), 0u);
}

TEST(ScratchArray, ElementsAreAlignedAsTheirTypeAsks) {
    struct alignas(64) Wide {
        float v[16];
    };
    for (const std::size_t count :
         {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(1000), std::size_t(40000)}) {
        auto a = makeScratchArray<Wide>(count);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.get()) % 64, 0u) << count;
        auto b = makeScratchArray<char>(count + 1);
        EXPECT_NE(b.get(), nullptr);
    }
}

TEST(ScratchArray, ImpossibleSizesThrow) {
    EXPECT_THROW(makeScratchArray<double>(std::size_t(1) << 61), std::bad_alloc);
}
