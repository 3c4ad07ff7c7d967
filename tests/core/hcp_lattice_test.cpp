#include "core/synth/hcp_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace faultline::core;

TEST(HcpLattice, PairsAreExactlyTheTouchingSpheres) {
    const HcpLattice lat = makeHcpLattice(5, 3, 4, 1.0);
    ASSERT_EQ(lat.size(), 60u);
    std::set<std::array<std::uint32_t, 2>> brute;
    for (std::uint32_t i = 0; i < lat.size(); ++i)
        for (std::uint32_t j = i + 1; j < lat.size(); ++j) {
            double d2 = 0;
            for (int a = 0; a < 3; ++a)
                d2 += (lat.positions[j][a] - lat.positions[i][a]) *
                      (lat.positions[j][a] - lat.positions[i][a]);
            EXPECT_GT(d2, 4.0 - 1e-9) << "spheres overlap: " << i << " " << j;
            if (d2 < 4.0 + 1e-9)
                brute.insert({i, j});
        }
    std::set<std::array<std::uint32_t, 2>> found(lat.pairs.begin(), lat.pairs.end());
    EXPECT_EQ(found.size(), lat.pairs.size());
    EXPECT_EQ(found, brute);
}

TEST(HcpLattice, InteriorSpheresHaveTwelveNeighbours) {
    const HcpLattice lat = makeHcpLattice(7, 5, 7, 1.0);
    std::vector<int> degree(lat.size(), 0);
    for (const auto& p : lat.pairs) {
        ++degree[p[0]];
        ++degree[p[1]];
    }
    // Column 3, layer 2, row 3 is away from every face.
    const std::size_t centre = (3 * 5 + 2) * 7 + 3;
    EXPECT_EQ(degree[centre], 12);
    for (int d : degree)
        EXPECT_LE(d, 12);
}

TEST(HcpLattice, BoxHoldsEverySphere) {
    const HcpLattice lat = makeHcpLattice(4, 2, 3, 1.0);
    EXPECT_DOUBLE_EQ(lat.hi[0], 10.0); // odd row of the odd layer: centre 9, plus the radius
    EXPECT_NEAR(lat.hi[1], 2.0 + 2.0 * std::sqrt(2.0 / 3.0), 1e-12);
    for (const auto& p : lat.positions)
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(p[a], 1.0 - 1e-12);
            EXPECT_LE(p[a] + 1.0, lat.hi[a] + 1e-12);
        }
}
