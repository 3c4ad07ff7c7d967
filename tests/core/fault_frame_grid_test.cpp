#include "core/faults/frame_grid.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

using namespace faultline::core;
using faultline::core::detail::FrameGrid;
using faultline::core::testing::frameOf;
using faultline::core::testing::Sphere;

TEST(FrameGrid, VisitsEverySphereNearAPlaneInsideTheBox) {
    std::mt19937 rng(3);
    std::vector<Sphere> s;
    for (int i = 0; i < 4000; ++i)
        s.push_back(
            {i, (rng() % 30000) / 1000.0, (rng() % 20000) / 1000.0, (rng() % 10000) / 1000.0});
    s.push_back({9000, NAN, 1, 1}); // never visited
    const Frame f = frameOf(s);
    for (double spc : {1.0, 8.0, 50.0}) {
        const FrameGrid grid(f, spc);
        EXPECT_EQ(grid.size(), 4000u);
        for (int trial = 0; trial < 20; ++trial) {
            const Vec3d n = normalFromOrientation(rng() % 91, rng() % 360);
            const Vec3d p{(rng() % 30000) / 1000.0, (rng() % 20000) / 1000.0,
                          (rng() % 10000) / 1000.0};
            const Vec3d lo{p[0] - 8, p[1] - 6, p[2] - 20}, hi{p[0] + 5, p[1] + 9, p[2] + 20};
            const double reach = 0.5 + trial * 0.2;
            std::set<std::uint32_t> visited;
            grid.forEachNearPlane(
                lo, hi, p, n, reach, [](const Vec3d&) { return true; },
                [&](std::uint32_t k) {
                    EXPECT_TRUE(visited.insert(grid.rows()[k]).second);
                    EXPECT_EQ(grid.xs()[k], f.x[grid.rows()[k]]);
                });
            for (std::size_t r = 0; r + 1 < f.size(); ++r) {
                const Vec3d q{f.x[r], f.y[r], f.z[r]};
                bool inBox = true;
                for (int a = 0; a < 3; ++a)
                    inBox = inBox && q[a] >= lo[a] && q[a] <= hi[a];
                const double d = n[0] * (q[0] - p[0]) + n[1] * (q[1] - p[1]) + n[2] * (q[2] - p[2]);
                if (inBox && std::fabs(d) <= reach) {
                    EXPECT_TRUE(visited.count(std::uint32_t(r))) << spc << " " << trial << " " << r;
                }
            }
        }
    }
}

TEST(FrameGrid, EmptyAndFlatFrames) {
    const FrameGrid empty(frameOf({}));
    EXPECT_EQ(empty.size(), 0u);
    const Frame flat = frameOf({{1, 0, 0, 0}, {2, 5, 0, 0}, {3, 10, 0, 0}});
    const FrameGrid grid(flat);
    std::vector<std::uint32_t> seen;
    grid.forEachNearPlane(
        {-1, -1, -1}, {11, 1, 1}, {5, 0, 0}, {1, 0, 0}, 0.5, [](const Vec3d&) { return true; },
        [&](std::uint32_t k) { seen.push_back(grid.rows()[k]); });
    EXPECT_EQ(seen, (std::vector<std::uint32_t>{1}));
}
