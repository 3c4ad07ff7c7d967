#include "core/synth/hcp_lattice.hpp"
#include "core/synth/local_strain.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace faultline::core;

namespace {
std::vector<std::array<double, 3>> mapped(const HcpLattice& lat, const double F[3][3]) {
    std::vector<std::array<double, 3>> out;
    for (const auto& p : lat.positions) {
        std::array<double, 3> q{};
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                q[a] += F[a][b] * p[b];
        out.push_back(q);
    }
    return out;
}
} // namespace

TEST(LocalStrain, NeighbourTableListsBothDirectionsInOrder) {
    const auto t = neighbourTableFromPairs(4, {{0, 2}, {0, 1}, {1, 3}});
    EXPECT_EQ(t.offsets, (std::vector<std::uint32_t>{0, 2, 4, 5, 6}));
    EXPECT_EQ(t.partners, (std::vector<std::uint32_t>{1, 2, 0, 3, 0, 1}));
}

TEST(LocalStrain, SimpleShearGivesTheExactInvariantEverywhere) {
    const HcpLattice lat = makeHcpLattice(5, 3, 5);
    const double g = 0.2;
    const double F[3][3] = {{1, 0, g}, {0, 1, 0}, {0, 0, 1}}; // x += g z
    const auto strain = vonMisesShearStrain(lat.positions, mapped(lat, F),
                                            neighbourTableFromPairs(lat.size(), lat.pairs));
    // E = [[0, 0, g/2], [0, 0, 0], [g/2, 0, g^2/2]]: sqrt(g^2/4 + (g^4/4 + g^4/4) / 6).
    const double expected = std::sqrt(g * g / 4 + g * g * g * g / 12);
    for (double s : strain)
        EXPECT_NEAR(s, expected, 1e-12);
}

TEST(LocalStrain, RigidRotationAndTranslationGiveZero) {
    const HcpLattice lat = makeHcpLattice(4, 2, 4);
    const double c = std::cos(0.7), s = std::sin(0.7);
    const double F[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
    auto moved = mapped(lat, F);
    for (auto& p : moved)
        p[2] += 5.0;
    const auto strain =
        vonMisesShearStrain(lat.positions, moved, neighbourTableFromPairs(lat.size(), lat.pairs));
    for (double v : strain)
        EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(LocalStrain, FewerThanThreeDirectionsGiveZero) {
    const std::vector<std::array<double, 3>> a = {{0, 0, 0}, {2, 0, 0}};
    const std::vector<std::array<double, 3>> b = {{0, 0, 0}, {3, 0, 0}};
    const auto strain = vonMisesShearStrain(a, b, neighbourTableFromPairs(2, {{0, 1}}));
    EXPECT_EQ(strain, (std::vector<double>{0.0, 0.0}));
}
