#include "core/faults/metrics.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace faultline::core;
using faultline::core::testing::faultOf;
using faultline::core::testing::frameOf;
using faultline::core::testing::Sphere;

namespace {

// Members: a 5 x 5 horizontal sheet at z = 0 (ids 1..25, x,y in 1..5). Above it, layers z = 1, 2
// displaced by (0.3, 0, -0.2) from x0 y0 z0; below, layers z = -1, -2 not displaced. Extra:
// a layer at z = 6 (beyond the sampled slab) and spheres at x = 20 (outside the footprint),
// both with large displacements that must not count.
Frame shearedSheet() {
    std::vector<Sphere> s;
    std::vector<float> x0, y0, z0;
    std::int64_t id = 1;
    auto add = [&](double x, double y, double z, double ux, double uz) {
        s.push_back({id++, x, y, z});
        x0.push_back(float(x - ux));
        y0.push_back(float(y));
        z0.push_back(float(z - uz));
    };
    for (int z : {0, 1, 2, -1, -2, 6})
        for (int i = 1; i <= 5; ++i)
            for (int j = 1; j <= 5; ++j) {
                if (z == 0)
                    add(i, j, 0, 0, 0);
                else if (z > 0 && z < 6)
                    add(i, j, z, 0.3, -0.2);
                else if (z < 0)
                    add(i, j, z, 0, 0);
                else
                    add(i, j, z, 9, 9);
            }
    for (int j = 1; j <= 5; ++j)
        add(20, j, 1, 9, 9);
    Frame f = frameOf(s);
    f.attributes.push_back(makeAttribute("x0", std::move(x0), false));
    f.attributes.push_back(makeAttribute("y0", std::move(y0), false));
    f.attributes.push_back(makeAttribute("z0", std::move(z0), false));
    f.finalize();
    return f;
}

std::vector<std::int64_t> range(std::int64_t first, std::int64_t last) {
    std::vector<std::int64_t> ids;
    for (std::int64_t i = first; i <= last; ++i)
        ids.push_back(i);
    return ids;
}
} // namespace

TEST(FaultMetrics, HorizontalSheetGeometryIsExact) {
    const Frame f = shearedSheet();
    const Fault fault = faultOf("F1", range(1, 25));
    const auto m = computeFrameMetrics(f, 4, std::vector<Fault>{fault}).at(0);
    EXPECT_EQ(m.frame, 4u);
    EXPECT_EQ(m.fault, 0u);
    EXPECT_EQ(m.name, "F1");
    EXPECT_EQ(m.count, 25u);
    EXPECT_EQ(m.min, (Vec3d{1, 1, 0}));
    EXPECT_EQ(m.max, (Vec3d{5, 5, 0}));
    EXPECT_EQ(m.centroid, (Vec3d{3, 3, 0}));
    ASSERT_TRUE(m.planeValid);
    EXPECT_EQ(m.dip, 0);
    EXPECT_EQ(m.dipDirection, 0);
    EXPECT_EQ(m.strike, 270);
    EXPECT_EQ(m.thickness, 0);
    EXPECT_EQ(m.meanRadius, 0.5);
    EXPECT_EQ(m.area, 25.0); // 25 cells of 1 x 1 (one diameter)
}

TEST(FaultMetrics, ThrowComparesHangingWallWithFootwall) {
    const Frame f = shearedSheet();
    const auto m = computeFrameMetrics(f, 0, std::vector<Fault>{faultOf("F", range(1, 25))}).at(0);
    ASSERT_EQ(m.throwStatus, ThrowStatus::Ok);
    EXPECT_EQ(m.hangingWallSamples, 50u); // z = 1, 2 inside the footprint
    EXPECT_EQ(m.footwallSamples, 50u);
    EXPECT_NEAR(m.slip[0], 0.3, 1e-6);
    EXPECT_NEAR(m.slip[1], 0.0, 1e-12);
    EXPECT_NEAR(m.throwVertical, -0.2, 1e-6);
    EXPECT_NEAR(m.netSlip, std::sqrt(0.13), 1e-6);
    EXPECT_NEAR(m.dipSlip, 0.0, 1e-12);    // down-dip of a flat plane is north
    EXPECT_NEAR(m.strikeSlip, -0.3, 1e-6); // strike of a flat plane is west
}

TEST(FaultMetrics, ThrowNeedsDisplacementColumnsAndEnoughSamples) {
    Frame f = frameOf({{1, 0, 0, 0}, {2, 1, 0, 0}, {3, 0, 1, 0}, {4, 1, 1, 0}});
    const std::vector<Fault> faults{faultOf("F", {1, 2, 3, 4})};
    auto m = computeFrameMetrics(f, 0, faults).at(0);
    EXPECT_EQ(m.throwStatus, ThrowStatus::NoDisplacement);
    EXPECT_TRUE(std::isnan(m.throwVertical));
    EXPECT_TRUE(std::isnan(m.netSlip));
    EXPECT_TRUE(m.planeValid);

    MetricsOptions off;
    off.computeThrow = false;
    EXPECT_EQ(computeFrameMetrics(f, 0, faults, off).at(0).throwStatus, ThrowStatus::Disabled);

    f.attributes.push_back(makeAttribute("x0", {0, 1, 0, 1}, false));
    f.attributes.push_back(makeAttribute("y0", {0, 0, 1, 1}, false));
    f.attributes.push_back(makeAttribute("z0", {0, 0, 0, 0}, false));
    f.finalize();
    m = computeFrameMetrics(f, 0, faults).at(0);
    EXPECT_EQ(m.throwStatus, ThrowStatus::TooFewSamples);
    EXPECT_EQ(m.hangingWallSamples, 0u);
    EXPECT_TRUE(std::isnan(m.throwVertical));
}

TEST(FaultMetrics, ThicknessIsTheWidthOfTheEquivalentUniformSlab) {
    std::vector<Sphere> s;
    std::int64_t id = 1;
    for (int z = 0; z <= 1; ++z)
        for (int x = 0; x <= 3; ++x)
            for (int y = 0; y <= 3; ++y)
                s.push_back({id++, double(x), double(y), double(z)});
    const Frame f = frameOf(s);
    const auto m = computeFrameMetrics(f, 0, std::vector<Fault>{faultOf("F", range(1, 32))}).at(0);
    ASSERT_TRUE(m.planeValid);
    EXPECT_EQ(m.dip, 0);
    EXPECT_NEAR(m.thickness, std::sqrt(3.0), 1e-12); // sqrt(12) x 0.5
    EXPECT_NEAR(m.eigenvalues[0], 0.25, 1e-12);
    EXPECT_EQ(m.area, 16.0); // two layers project onto the same 16 cells
}

TEST(FaultMetrics, MembersAbsentFromTheFrameAreNotCounted) {
    const Frame f = frameOf({{1, 0, 0, 0}, {2, 2, 0, 0}, {5, 9, 9, 9}});
    const auto m = computeFrameMetrics(f, 0, std::vector<Fault>{faultOf("F", {1, 2, 3, 4})}).at(0);
    EXPECT_EQ(m.count, 2u);
    EXPECT_EQ(m.centroid, (Vec3d{1, 0, 0}));
    EXPECT_FALSE(m.planeValid);
    EXPECT_TRUE(std::isnan(m.dip));
    EXPECT_TRUE(std::isnan(m.thickness));
    EXPECT_TRUE(std::isnan(m.area));
    EXPECT_EQ(m.throwStatus, ThrowStatus::NoDisplacement);
}

TEST(FaultMetrics, EmptyFaultIsAllUndefined) {
    const Frame f = frameOf({{1, 0, 0, 0}});
    const auto m = computeFrameMetrics(f, 0, std::vector<Fault>{faultOf("E", {})}).at(0);
    EXPECT_EQ(m.count, 0u);
    EXPECT_TRUE(std::isnan(m.centroid[0]));
    EXPECT_TRUE(std::isnan(m.min[0]));
    EXPECT_TRUE(std::isnan(m.meanRadius));
    EXPECT_EQ(m.broken, 0u);
}

TEST(FaultMetrics, SeedIsWhereMembersFirstBroke) {
    // ids 1..4 at x = 0, 2, 4, 6; id 9 is not a member and breaks first.
    std::vector<std::shared_ptr<const Frame>> frames;
    const std::vector<std::vector<float>> broken{{0, 0, 0, 0, 3}, {0, 2, 0, 1, 3}, {1, 2, 5, 1, 3}};
    for (const auto& b : broken) {
        Frame f = frameOf({{1, 0, 0, 0}, {2, 2, 0, 0}, {3, 4, 0, 0}, {4, 6, 0, 0}, {9, 0, 5, 0}});
        f.attributes.push_back(makeAttribute("broken_bonds", std::vector<float>(b), true));
        f.finalize();
        frames.push_back(std::make_shared<const Frame>(std::move(f)));
    }
    const std::vector<Fault> faults{faultOf("F", {1, 2, 3, 4}), faultOf("Quiet", {9})};
    FaultMetricsSeries series = computeMetricsSeries(
        frames.size(), [&](std::size_t i) { return frames[i]; }, faults);
    ASSERT_EQ(series.rows.size(), 6u);
    EXPECT_EQ(series.at(0, 0).broken, 0u);
    EXPECT_EQ(series.at(1, 0).broken, 2u);
    EXPECT_EQ(series.at(2, 0).broken, 4u);
    ASSERT_TRUE(series.seeds[0].found);
    EXPECT_EQ(series.seeds[0].frame, 1u);
    EXPECT_EQ(series.seeds[0].count, 2u);
    EXPECT_EQ(series.seeds[0].point, (Vec3d{4, 0, 0})); // ids 2 and 4
    ASSERT_TRUE(series.seeds[1].found);
    EXPECT_EQ(series.seeds[1].frame, 0u);

    MetricsOptions other;
    other.brokenBondsVariable = "damage";
    const auto none = computeMetricsSeries(
        frames.size(), [&](std::size_t i) { return frames[i]; }, faults, other);
    EXPECT_FALSE(none.seeds[0].found);
}

TEST(FaultMetrics, SeriesRowsEqualPerFrameMetrics) {
    std::vector<std::shared_ptr<const Frame>> frames;
    for (int t = 0; t < 4; ++t) {
        std::vector<Sphere> s;
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j)
                s.push_back({i * 6 + j + 1, double(i), double(j), 0.1 * t * i});
        frames.push_back(std::make_shared<const Frame>(frameOf(s)));
    }
    const std::vector<Fault> faults{faultOf("A", range(1, 36)), faultOf("B", range(1, 12))};
    const auto series = computeMetricsSeries(
        frames.size(), [&](std::size_t i) { return frames[i]; }, faults);
    for (std::size_t t = 0; t < frames.size(); ++t) {
        const auto rows = computeFrameMetrics(*frames[t], t, faults);
        for (std::size_t k = 0; k < faults.size(); ++k) {
            EXPECT_EQ(series.at(t, k).frame, t);
            EXPECT_EQ(series.at(t, k).dip, rows[k].dip);
            EXPECT_EQ(series.at(t, k).area, rows[k].area);
        }
    }
    // A tilts to the east as the frames go: tan(dip) = 0.1 t
    for (int t = 1; t < 4; ++t) {
        EXPECT_NEAR(series.at(t, 0).dip, std::atan(0.1 * t) * 180 / 3.141592653589793, 1e-4);
        EXPECT_NEAR(series.at(t, 0).dipDirection, 270, 1e-4);
    }
}
