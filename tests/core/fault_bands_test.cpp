#include "core/synth/fault_bands.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace faultline::core;

namespace {
// Spheres on a grid (x 0..99, z 0..39); those on the given lines get broken bonds.
Frame gridFrame(const std::vector<std::pair<double, double>>& lines) {
    Frame f;
    std::vector<std::int32_t> broken, type;
    std::int64_t id = 1;
    for (int z = 0; z < 40; ++z)
        for (int x = 0; x < 100; ++x) {
            f.ids.push_back(id++);
            f.x.push_back(static_cast<float>(x));
            f.y.push_back(0);
            f.z.push_back(static_cast<float>(z));
            f.radius.push_back(0.5f);
            int b = 0;
            // Line through (x0, 0) dipping `dip` towards +x: x = x0 + z / tan(dip)... up-dip is -x.
            for (const auto& [x0, dip] : lines) {
                const double onLine = x0 - z / std::tan(dip * std::numbers::pi / 180);
                if (std::fabs(x - onLine) < 0.5)
                    b = 4;
            }
            broken.push_back(b);
            type.push_back(1);
        }
    AttributeColumn bc;
    bc.name = "broken_bonds";
    bc.type = ColumnType::Int32;
    bc.ints = broken;
    AttributeColumn tc;
    tc.name = "type";
    tc.type = ColumnType::Int32;
    tc.ints = type;
    f.attributes = {tc, bc};
    f.finalize();
    return f;
}
} // namespace

TEST(FaultBands, FindsTwoLinesAndTheirDips) {
    // 45 degrees from x = 70: 40 spheres; 60 degrees from x = 20: 35 (it leaves the grid).
    const Frame f = gridFrame({{20.0, 60.0}, {70.0, 45.0}});
    FaultBandOptions o;
    o.bands = 2;
    o.width = 3;
    const auto m = measureFaultBands(f, o);
    ASSERT_EQ(m.bands.size(), 2u);
    EXPECT_DOUBLE_EQ(m.damagedShare, 1.0);
    // Both lines go down towards +x; the longer one comes first.
    EXPECT_EQ(m.bands[0].towardsPlusX, 1);
    EXPECT_NEAR(m.bands[0].dip, 45, 2);
    EXPECT_NEAR(m.bands[1].dip, 60, 2);
    EXPECT_LT(m.uniformShare, 0.2);
    EXPECT_GT(m.concentration(), 5);
}

TEST(FaultBands, NoDamageMeansNoBands) {
    const auto m = measureFaultBands(gridFrame({}));
    EXPECT_TRUE(m.bands.empty());
    EXPECT_EQ(m.damagedShare, 0.0);
    EXPECT_EQ(m.concentration(), 0.0);
}
