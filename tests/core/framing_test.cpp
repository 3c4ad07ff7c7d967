// What fitting a view frames (core/view/framing): a granular run's few far strays are left out;
// a model without strays, and a shape with a long tail, keep every centre's bounds.
#include "core/view/framing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace faultline::core;

namespace {

// A jittered block of n x n/2 x n/3 spheres (spacing 1), ids 1...
Frame block(int n) {
    Frame f;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    for (int k = 0; k < n / 3; ++k)
        for (int j = 0; j < n / 2; ++j)
            for (int i = 0; i < n; ++i) {
                f.ids.push_back(static_cast<std::int64_t>(f.ids.size()) + 1);
                f.x.push_back(static_cast<float>(i + jitter(rng)));
                f.y.push_back(static_cast<float>(j + jitter(rng)));
                f.z.push_back(static_cast<float>(k + jitter(rng)));
            }
    f.radius.assign(f.ids.size(), 0.5f);
    return f;
}

} // namespace

TEST(Framing, ABlockIsFramedByAllItsCentres) {
    Frame f = block(30);
    f.finalize();
    const Framing framing = framingBounds(f);
    EXPECT_EQ(framing.strays, 0u);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(framing.lo[a], f.centreMin()[a]);
        EXPECT_EQ(framing.hi[a], f.centreMax()[a]);
    }
}

// As in the Yade sandbox run without a floor: a handful of grains fall far below the model
// (ten model heights), and one shot sideways; a NaN centre counts for nothing.
TEST(Framing, AFewFarStraysAreLeftOut) {
    Frame f = block(30); // 30 x 15 x 10: z from 0 to 9
    f.finalize();
    const std::array<double, 3> lo{f.centreMin()[0], f.centreMin()[1], f.centreMin()[2]};
    const std::array<double, 3> hi{f.centreMax()[0], f.centreMax()[1], f.centreMax()[2]};
    for (int k = 0; k < 12; ++k) {
        f.z[std::size_t(100 + 37 * k)] = static_cast<float>(-90.0 - k);
    }
    f.x[500] = 400.0f;
    f.y[700] = std::numeric_limits<float>::quiet_NaN();
    f.finalize();
    const Framing framing = framingBounds(f);
    EXPECT_EQ(framing.strays, 13u);
    EXPECT_NEAR(framing.lo[2], lo[2], 0.2);
    EXPECT_NEAR(framing.hi[2], hi[2], 0.2);
    EXPECT_NEAR(framing.hi[0], hi[0], 0.2);
    EXPECT_NEAR(framing.lo[0], lo[0], 0.2);
    EXPECT_LT(f.centreMin()[2], -100.0f); // the frame's own bounds hold them
}

// A cone (a heap) up to its apex, and a model a quarter of which slid away: shapes, framed
// whole (the block's and the slid quarter's centres are all within the bulk and its margin).
TEST(Framing, ShapesWithTailsAreNotStrays) {
    Frame cone;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    while (cone.ids.size() < 20000) {
        const double x = 20 * u(rng), y = 20 * u(rng), z = 20 * (0.5 + 0.5 * u(rng));
        if (std::hypot(x, y) > 20 - z)
            continue;
        cone.ids.push_back(static_cast<std::int64_t>(cone.ids.size()) + 1);
        cone.x.push_back(float(x)), cone.y.push_back(float(y)), cone.z.push_back(float(z));
    }
    cone.radius.assign(cone.ids.size(), 0.3f);
    cone.finalize();
    Framing framing = framingBounds(cone);
    EXPECT_EQ(framing.strays, 0u);
    EXPECT_EQ(framing.hi[2], cone.centreMax()[2]);

    Frame slid = block(30);
    for (std::size_t i = 0; i < slid.size() / 4; ++i)
        slid.z[i] -= 60.0f;
    slid.finalize();
    framing = framingBounds(slid);
    EXPECT_EQ(framing.strays, 0u);
    EXPECT_EQ(framing.lo[2], slid.centreMin()[2]);
}

// Grains falling out on one side, up to 5 % of the model, are left out; more than that is the
// model's shape, framed whole.
TEST(Framing, StraysOnOneSideUpToAShare) {
    for (const double share : {0.03, 0.08}) {
        Frame f = block(30); // 4,500 spheres
        const std::size_t fallen = std::size_t(share * double(f.size()));
        for (std::size_t k = 0; k < fallen; ++k)
            f.z[k * (f.size() / fallen)] = static_cast<float>(-50.0 - double(k) * 0.1);
        f.finalize();
        const Framing framing = framingBounds(f);
        SCOPED_TRACE(share);
        if (share < 0.05) {
            EXPECT_EQ(framing.strays, fallen);
            EXPECT_GT(framing.lo[2], -1.0);
        } else {
            EXPECT_EQ(framing.strays, 0u);
            EXPECT_EQ(framing.lo[2], f.centreMin()[2]);
        }
    }
}

// An infinite coordinate (a float overflowed on reading) is no centre: the bounds stay finite.
TEST(Framing, InfiniteCentresAreLeftOut) {
    Frame f = block(12);
    f.x[5] = std::numeric_limits<float>::infinity();
    f.finalize();
    const Framing framing = framingBounds(f);
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(std::isfinite(framing.lo[a]));
        EXPECT_TRUE(std::isfinite(framing.hi[a]));
    }
    EXPECT_NEAR(framing.hi[0], 11.0, 0.2);
}

TEST(Framing, AnEmptyFrameHasNoBounds) {
    Frame f;
    f.finalize();
    const Framing framing = framingBounds(f);
    EXPECT_EQ(framing.strays, 0u);
    EXPECT_EQ(framing.lo[0], 0.0);
}
