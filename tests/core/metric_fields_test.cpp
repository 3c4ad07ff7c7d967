// The metrics by name: values of a horizontal sheet, and NaN where a metric is undefined.
#include "core/faults/metric_fields.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace faultline::core;
using faultline::core::testing::faultOf;
using faultline::core::testing::frameOf;
using faultline::core::testing::Sphere;

namespace {
double valueOf(std::string_view key, const FaultFrameMetrics& m) {
    const MetricField* f = findMetricField(key);
    EXPECT_NE(f, nullptr) << key;
    return f ? f->value(m) : 0.0;
}
} // namespace

TEST(MetricFields, KeysAreUniqueAndFindable) {
    std::set<std::string_view> keys;
    for (const MetricField& f : metricFields()) {
        EXPECT_TRUE(keys.insert(f.key).second) << f.key;
        EXPECT_EQ(findMetricField(f.key), &f);
        EXPECT_FALSE(f.label.empty());
    }
    EXPECT_EQ(metricFields().front().key, "count");
    EXPECT_EQ(findMetricField("no such metric"), nullptr);
}

TEST(MetricFields, ASheetsValuesAndTheUndefinedOnes) {
    // A 4 x 3 sheet at z = 2 (ids 1..12), x in 0..3, y in 0..2; no displacement columns.
    std::vector<Sphere> s;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i)
            s.push_back({1 + i + 4 * j, double(i), double(j), 2.0});
    const Frame frame = frameOf(s);
    const std::vector<Fault> faults{faultOf("sheet", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}),
                                    faultOf("pair", {1, 2}), faultOf("absent", {99})};
    const auto m = computeFrameMetrics(frame, 0, faults);
    ASSERT_EQ(m.size(), 3u);
    EXPECT_EQ(valueOf("count", m[0]), 12.0);
    EXPECT_NEAR(valueOf("dip", m[0]), 0.0, 1e-9);
    EXPECT_NEAR(valueOf("thickness", m[0]), 0.0, 1e-9);
    EXPECT_EQ(valueOf("extent_x", m[0]), 3.0);
    EXPECT_EQ(valueOf("extent_y", m[0]), 2.0);
    EXPECT_EQ(valueOf("extent_z", m[0]), 0.0);
    EXPECT_NEAR(valueOf("centroid_x", m[0]), 1.5, 1e-12);
    EXPECT_NEAR(valueOf("centroid_z", m[0]), 2.0, 1e-12);
    EXPECT_EQ(valueOf("mean_radius", m[0]), 0.5);
    EXPECT_EQ(valueOf("broken", m[0]), 0.0);
    EXPECT_TRUE(std::isnan(valueOf("throw", m[0]))); // no x0 y0 z0 columns
    // Two members make no plane.
    EXPECT_EQ(valueOf("count", m[1]), 2.0);
    EXPECT_TRUE(std::isnan(valueOf("dip", m[1])));
    EXPECT_TRUE(std::isnan(valueOf("area", m[1])));
    EXPECT_EQ(valueOf("extent_x", m[1]), 1.0);
    // No members present: a count of 0, everything else undefined or zero.
    EXPECT_EQ(valueOf("count", m[2]), 0.0);
    EXPECT_TRUE(std::isnan(valueOf("extent_x", m[2])));
    EXPECT_TRUE(std::isnan(valueOf("centroid_y", m[2])));
    EXPECT_TRUE(std::isnan(valueOf("dip_direction", m[2])));
}
