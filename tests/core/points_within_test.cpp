// pointsWithin: the points within reach in their order, and every squared distance as the
// scalar expression rounds it, whatever the count (whole vectors and a partial last one).
#include "core/util/points_within.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace faultline::core;

TEST(PointsWithin, MatchesTheScalarLoopForEveryCount) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t m = 0; m <= 37; ++m) {
        // Eight more than m, as the function asks; the extra ones hold points within reach,
        // which must not be counted.
        std::vector<float> x(m + 8, 0.0f), y(m + 8, 0.0f), z(m + 8, 0.0f), d2(m + 8);
        std::vector<std::uint32_t> within(m + 8, 99);
        for (std::size_t t = 0; t < m; ++t)
            x[t] = u(rng), y[t] = u(rng), z[t] = u(rng);
        if (m > 3)
            y[3] = nan; // never within reach
        const float px = 0.25f, py = -0.5f, pz = 1.0f, r2 = 4.0f;
        if (m > 5) // exactly on the limit: within
            x[5] = px + 2.0f, y[5] = py, z[5] = pz;
        const std::size_t n =
            pointsWithin(x.data(), y.data(), z.data(), m, px, py, pz, r2, d2.data(), within.data());
        std::vector<std::uint32_t> expected;
        for (std::size_t t = 0; t < m; ++t) {
            const float dx = px - x[t], dy = py - y[t], dz = pz - z[t];
            const float e = dx * dx + dy * dy + dz * dz;
            if (std::isnan(e))
                EXPECT_TRUE(std::isnan(d2[t])) << "m " << m << ", point " << t;
            else
                EXPECT_EQ(d2[t], e) << "m " << m << ", point " << t;
            if (e <= r2)
                expected.push_back(std::uint32_t(t));
        }
        ASSERT_EQ(n, expected.size()) << "m " << m;
        for (std::size_t k = 0; k < n; ++k)
            EXPECT_EQ(within[k], expected[k]) << "m " << m << ", " << k;
        if (m > 5) {
            EXPECT_NE(std::find(within.begin(), within.begin() + std::ptrdiff_t(n), 5u),
                      within.begin() + std::ptrdiff_t(n))
                << "a point exactly at the limit is within reach";
        }
    }
}
