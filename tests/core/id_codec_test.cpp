#include "core/io/base64.hpp"
#include "core/session/id_codec.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace faultline::core;

TEST(IdCodec, RoundTripsEdgeCases) {
    const std::vector<std::vector<std::int64_t>> cases = {
        {},
        {0},
        {-5},
        {1, 2, 3},
        {-9000000000000000000LL, -1, 0, 7, 9000000000000000000LL},
        {INT64_MIN, INT64_MAX},
        {INT64_MAX}};
    for (const auto& ids : cases) {
        std::string error;
        auto back = unpackSortedIds(packSortedIds(ids), error);
        ASSERT_TRUE(back) << error;
        EXPECT_EQ(*back, ids);
    }
}

TEST(IdCodec, RoundTripsLargeRandomSets) {
    std::mt19937_64 rng(3);
    std::vector<std::int64_t> ids(100000);
    for (auto& id : ids)
        id = static_cast<std::int64_t>(rng() % 5000000);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const std::string packed = packSortedIds(ids);
    EXPECT_LT(packed.size(), ids.size() * 2); // gaps of ~50 take one byte each, 4/3 in base64
    std::string error;
    EXPECT_EQ(unpackSortedIds(packed, error), ids);
}

TEST(IdCodec, BadTextIsAnErrorNotACrash) {
    std::string error;
    EXPECT_FALSE(unpackSortedIds("@@@@", error));
    EXPECT_NE(error.find("bad base64"), std::string::npos);
    EXPECT_FALSE(unpackSortedIds("gA==", error)); // 0x80: a varint that never ends
    EXPECT_NE(error.find("truncated"), std::string::npos);
    // First id INT64_MAX - 1 (zigzag 0xFFFFFFFFFFFFFFFC), then a gap of 5: beyond int64.
    const std::string bytes = std::string("\xfc\xff\xff\xff\xff\xff\xff\xff\xff\x01", 10) + "\x05";
    EXPECT_FALSE(unpackSortedIds(encodeBase64(bytes), error));
    EXPECT_NE(error.find("beyond the 64-bit range"), std::string::npos);
}
