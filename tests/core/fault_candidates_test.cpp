#include "core/faults/candidates.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>

using namespace faultline::core;
using faultline::core::testing::frameOf;
using faultline::core::testing::Sphere;

namespace {
std::vector<std::vector<std::int64_t>> idsOf(const CandidateSet& set) {
    std::vector<std::vector<std::int64_t>> out;
    for (const auto& c : set.candidates)
        out.push_back(c.ids);
    return out;
}
std::vector<std::uint8_t> allVisible(const Frame& f) {
    return std::vector<std::uint8_t>(f.size(), 1);
}
// These tests are about the connected method: linking by distance alone.
CandidateOptions connected(double link = kDefaultCandidateLink, std::size_t minSize = 1) {
    CandidateOptions o;
    o.method = CandidateMethod::Connected;
    o.link = link;
    o.minSize = minSize;
    return o;
}

// O(n^2) reference: the same neighbour rule, components as sorted id lists in a set.
std::set<std::vector<std::int64_t>> bruteForce(const Frame& f, const std::vector<std::uint8_t>& vis,
                                               double k) {
    const std::size_t n = f.size();
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](std::size_t x) {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];
        return x;
    };
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            if (!vis[i] || !vis[j])
                continue;
            const double dx = double(f.x[i]) - f.x[j], dy = double(f.y[i]) - f.y[j],
                         dz = double(f.z[i]) - f.z[j];
            const double lim = k * (double(f.radius[i]) + f.radius[j]);
            if (dx * dx + dy * dy + dz * dz < lim * lim)
                parent[find(i)] = find(j);
        }
    std::map<std::size_t, std::vector<std::int64_t>> groups;
    for (std::size_t i = 0; i < n; ++i)
        if (vis[i])
            groups[find(i)].push_back(f.ids[i]);
    std::set<std::vector<std::int64_t>> out;
    for (auto& [root, ids] : groups) {
        std::sort(ids.begin(), ids.end());
        out.insert(ids);
    }
    return out;
}
} // namespace

TEST(FaultCandidates, TwoSeparatedClustersGiveTwoCandidatesLargestFirst) {
    const Frame f = frameOf({{10, 0, 0, 0},
                             {11, 1, 0, 0},
                             {12, 2, 0, 0}, // a line of 3
                             {20, 10, 0, 0},
                             {21, 10, 1, 0}}); // a pair, far away
    const CandidateSet set = findCandidates(f, allVisible(f), connected());
    ASSERT_EQ(set.candidates.size(), 2u);
    EXPECT_EQ(set.candidates[0].ids, (std::vector<std::int64_t>{10, 11, 12}));
    EXPECT_EQ(set.candidates[1].ids, (std::vector<std::int64_t>{20, 21}));
    EXPECT_EQ(set.rowLabel, (std::vector<std::int32_t>{0, 0, 0, 1, 1}));
}

TEST(FaultCandidates, LinkDistanceIsStrict) {
    // radius 0.5 each: neighbours when distance < link x 1.0
    const Frame touching = frameOf({{1, 0, 0, 0}, {2, 1, 0, 0}});
    EXPECT_EQ(findCandidates(touching, allVisible(touching), connected(1.0, 1)).candidates.size(),
              2u);
    EXPECT_EQ(findCandidates(touching, allVisible(touching), connected(1.001, 1)).candidates.size(),
              1u);

    const Frame inside = frameOf({{1, 0, 0, 0}, {2, 0, 1.0999, 0}});
    const Frame outside = frameOf({{1, 0, 0, 0}, {2, 0, 0, 1.1001}});
    EXPECT_EQ(findCandidates(inside, allVisible(inside), connected()).candidates.size(),
              1u); // default 1.1
    EXPECT_EQ(findCandidates(outside, allVisible(outside), connected()).candidates.size(), 2u);
}

TEST(FaultCandidates, LinkDistanceUsesBothRadii) {
    // 1.1 x (1.0 + 0.25) = 1.375
    const Frame near = frameOf({{1, 0, 0, 0, 1.0}, {2, 1.3, 0, 0, 0.25}});
    const Frame far = frameOf({{1, 0, 0, 0, 1.0}, {2, 1.45, 0, 0, 0.25}});
    EXPECT_EQ(findCandidates(near, allVisible(near), connected()).candidates.size(), 1u);
    EXPECT_EQ(findCandidates(far, allVisible(far), connected()).candidates.size(), 2u);
}

TEST(FaultCandidates, MinSizeDropsSmallComponentsAndHiddenSpheresAreUnlabelled) {
    std::vector<Sphere> s;
    for (int i = 0; i < 5; ++i)
        s.push_back({100 + i, double(i), 0, 0}); // 5 in a line
    for (int i = 0; i < 3; ++i)
        s.push_back({200 + i, double(i), 10, 0}); // 3 in a line
    s.push_back({300, 0, 20, 0});                 // alone
    s.push_back({400, 0, 30, 0});                 // hidden
    const Frame f = frameOf(s);
    std::vector<std::uint8_t> vis(f.size(), 1);
    vis.back() = 0;
    const CandidateSet set = findCandidates(f, vis, connected(1.1, 3));
    ASSERT_EQ(set.candidates.size(), 2u);
    EXPECT_EQ(set.candidates[0].size(), 5u);
    EXPECT_EQ(set.candidates[1].ids, (std::vector<std::int64_t>{200, 201, 202}));
    EXPECT_EQ(set.rowLabel[8], -1); // too small
    EXPECT_EQ(set.rowLabel[9], -1); // hidden
    EXPECT_EQ(findCandidates(f, vis, connected(1.1, 6)).candidates.size(), 0u);
    EXPECT_EQ(findCandidates(f, vis, connected(1.1, 0)).candidates.size(), 3u); // 0 acts as 1
}

TEST(FaultCandidates, HiddenSphereBreaksAChain) {
    const Frame f = frameOf({{1, 0, 0, 0}, {2, 1, 0, 0}, {3, 2, 0, 0}});
    const std::vector<std::uint8_t> vis{1, 0, 1};
    const CandidateSet set = findCandidates(f, vis, connected());
    EXPECT_EQ(idsOf(set), (std::vector<std::vector<std::int64_t>>{{1}, {3}}));
}

TEST(FaultCandidates, EqualSizesAreOrderedBySmallestIdWhateverTheRowOrder) {
    const std::vector<Sphere> a{{50, 0, 0, 0}, {7, 1, 0, 0},   {90, 5, 0, 0},
                                {3, 6, 0, 0},  {60, 20, 0, 0}, {61, 21, 0, 0}};
    std::vector<Sphere> b(a.rbegin(), a.rend());
    const Frame fa = frameOf(a), fb = frameOf(b);
    const auto expected = std::vector<std::vector<std::int64_t>>{{3, 90}, {7, 50}, {60, 61}};
    EXPECT_EQ(idsOf(findCandidates(fa, allVisible(fa), connected())), expected);
    EXPECT_EQ(idsOf(findCandidates(fb, allVisible(fb), connected())), expected);
}

TEST(FaultCandidates, NonFiniteSpheresStandAlone) {
    const Frame f = frameOf({{1, 0, 0, 0}, {2, NAN, 0, 0}, {3, 1, 0, 0}, {4, 0.5, 0, 0, NAN}});
    const CandidateSet set = findCandidates(f, allVisible(f), connected());
    EXPECT_EQ(idsOf(set), (std::vector<std::vector<std::int64_t>>{{1, 3}, {2}, {4}}));
}

TEST(FaultCandidates, NothingVisibleGivesNothing) {
    const Frame f = frameOf({{1, 0, 0, 0}});
    const CandidateSet set = findCandidates(f, std::vector<std::uint8_t>{0}, connected());
    EXPECT_TRUE(set.candidates.empty());
    EXPECT_EQ(set.rowLabel, (std::vector<std::int32_t>{-1}));
}

TEST(FaultCandidates, BadLinkFactorIsRejected) {
    const Frame f = frameOf({{1, 0, 0, 0}});
    EXPECT_THROW(findCandidates(f, allVisible(f), connected(0.0, 1)), std::invalid_argument);
    EXPECT_THROW(findCandidates(f, allVisible(f), connected(NAN, 1)), std::invalid_argument);
}

TEST(FaultCandidates, ZeroRadiiLinkNothing) {
    const Frame f = frameOf({{1, 0, 0, 0, 0.0}, {2, 0, 0, 0, 0.0}});
    EXPECT_EQ(findCandidates(f, allVisible(f), connected()).candidates.size(), 2u);
}

TEST(FaultCandidates, RandomPolydisperseSpheresMatchBruteForce) {
    std::mt19937 rng(11);
    std::vector<Sphere> s;
    for (int i = 0; i < 1500; ++i)
        s.push_back({i * 3 + 1, (rng() % 20000) / 1000.0, (rng() % 20000) / 1000.0,
                     (rng() % 8000) / 1000.0, 0.2 + (rng() % 300) / 1000.0});
    const Frame f = frameOf(s);
    std::vector<std::uint8_t> vis(f.size());
    for (auto& v : vis)
        v = rng() % 4 != 0;
    for (double k : {0.8, 1.1, 1.6}) {
        const CandidateSet set = findCandidates(f, vis, connected(k, 1));
        const auto expected = bruteForce(f, vis, k);
        const auto got = idsOf(set);
        EXPECT_EQ(std::set<std::vector<std::int64_t>>(got.begin(), got.end()), expected) << k;
        EXPECT_EQ(got.size(), expected.size());
        for (std::size_t i = 1; i < got.size(); ++i)
            EXPECT_TRUE(got[i - 1].size() > got[i].size() ||
                        (got[i - 1].size() == got[i].size() && got[i - 1][0] < got[i][0]));
        for (std::size_t r = 0; r < f.size(); ++r) {
            if (!vis[r]) {
                EXPECT_EQ(set.rowLabel[r], -1);
                continue;
            }
            ASSERT_GE(set.rowLabel[r], 0);
            EXPECT_TRUE(std::binary_search(got[set.rowLabel[r]].begin(), got[set.rowLabel[r]].end(),
                                           f.ids[r]));
        }
    }
}

TEST(FaultCandidates, AcceptingAllNamesThemWithThePrefixLargestFirst) {
    const Frame f = frameOf({{10, 0, 0, 0}, {11, 1, 0, 0}, {20, 10, 0, 0}});
    const CandidateSet set = findCandidates(f, allVisible(f), connected());
    const std::vector<Fault> faults = faultsFromCandidates(set.candidates, "C");
    ASSERT_EQ(faults.size(), 2u);
    EXPECT_EQ(faults[0].name, "C1");
    EXPECT_EQ(faults[0].ids, (std::vector<std::int64_t>{10, 11}));
    EXPECT_EQ(faults[1].name, "C2");
    EXPECT_EQ(faults[1].ids, (std::vector<std::int64_t>{20}));
    EXPECT_NE(faults[0].color, faults[1].color);
    EXPECT_TRUE(faults[0].notes.empty());
}

TEST(FaultCandidates, ColoursAreDistinctAndInRange) {
    std::set<std::array<float, 3>> seen;
    for (std::size_t i = 0; i < 64; ++i) {
        const auto c = candidateColor(i);
        for (float v : c) {
            EXPECT_GE(v, 0.0f);
            EXPECT_LE(v, 1.0f);
        }
        seen.insert(c);
    }
    EXPECT_EQ(seen.size(), 64u);
}

// Walkthrough of issue 41, item 11: the demo's graben-centre damage (sub-vertical, thickness
// ratio 0.33 and 0.39) was not called diffuse under a limit of 0.5, while its faults read
// 0.18-0.20. In 3-D a zone thick for its width is diffuse from 0.3; in a section model real
// shear bands read up to 0.35, and the limit there stays 0.5.
TEST(FaultCandidates, ThickBlobsAreDiffuseThickFaultZonesAreNot) {
    // A block of spheres on a unit lattice, 80 (x) by 60 (y) by 70 (z), from which groups are
    // taken by shape: the block itself is 3-D, not a section.
    std::vector<Sphere> spheres;
    std::int64_t id = 1;
    for (int x = 0; x < 80; ++x)
        for (int y = 0; y < 60; ++y)
            for (int z = 0; z < 70; z += 2)
                spheres.push_back({id++, double(x), double(y), double(z)});
    const Frame block = frameOf(spheres);
    auto idsWhere = [&](auto inside) {
        std::vector<std::int64_t> ids;
        for (std::size_t i = 0; i < block.size(); ++i)
            if (inside(double(block.x[i]), double(block.y[i]), double(block.z[i])))
                ids.push_back(block.ids[i]);
        return ids;
    };
    // A fault zone 6 thick dipping 60 degrees, across the whole block: ratio about 0.1.
    const double c = std::cos(60 * M_PI / 180), s = std::sin(60 * M_PI / 180);
    const CandidateShape zone =
        candidateShape(block, idsWhere([&](double x, double, double z) {
                           return std::fabs((x - 40) * s + (z - 35) * c) < 3;
                       }));
    ASSERT_TRUE(zone.valid);
    EXPECT_FALSE(zone.diffuse) << zone.thicknessRatio;
    EXPECT_NEAR(zone.dip, 60, 1);
    // Damage filling a vertical slab 16 thick, 40 wide and 56 high: ratio about 0.4.
    const CandidateShape blob =
        candidateShape(block, idsWhere([](double x, double y, double z) {
                           return x >= 30 && x < 46 && y >= 10 && y < 50 && z >= 6 && z < 62;
                       }));
    ASSERT_TRUE(blob.valid);
    EXPECT_GT(blob.thicknessRatio, 0.3);
    EXPECT_LT(blob.thicknessRatio, 0.5);
    EXPECT_TRUE(blob.diffuse) << blob.thicknessRatio;
    // The same proportions in a section model (3 spheres deep in y): a thick band, not diffuse.
    std::vector<Sphere> slab;
    id = 1;
    for (int x = 0; x < 80; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 70; ++z)
                slab.push_back({id++, double(x), double(y), double(z)});
    const Frame section = frameOf(slab);
    std::vector<std::int64_t> band;
    for (std::size_t i = 0; i < section.size(); ++i) {
        const double x = section.x[i], z = section.z[i];
        const double along = (x - 40) * c - (z - 35) * s, across = (x - 40) * s + (z - 35) * c;
        if (std::fabs(across) < 5 && std::fabs(along) < 14)
            band.push_back(section.ids[i]);
    }
    const CandidateShape thickBand = candidateShape(section, band);
    ASSERT_TRUE(thickBand.valid);
    EXPECT_GT(thickBand.thicknessRatio, 0.3);
    EXPECT_FALSE(thickBand.diffuse) << thickBand.thicknessRatio;
}
