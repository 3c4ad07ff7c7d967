#include "core/model/frame_difference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace faultline::core;

namespace {

Frame makeFrame(std::vector<std::int64_t> ids, std::vector<float> x, std::vector<float> y,
                std::vector<float> z, std::vector<float> strain, std::vector<std::int32_t> bonds) {
    Frame f;
    f.ids = std::move(ids);
    f.x = std::move(x);
    f.y = std::move(y);
    f.z = std::move(z);
    f.radius.assign(f.ids.size(), 0.5f);
    AttributeColumn s;
    s.name = "strain";
    s.floats = std::move(strain);
    AttributeColumn b;
    b.name = "broken_bonds";
    b.type = ColumnType::Int32;
    b.ints = std::move(bonds);
    f.attributes = {s, b};
    f.finalize();
    return f;
}

} // namespace

TEST(FrameDifference, ChangeMatchedByIdWithNaNForMissing) {
    const Frame now = makeFrame({1, 2, 3, 4}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0},
                                {0.5f, 0.75f, 1.0f, 2.0f}, {3, 5, 7, 9});
    const Frame before =
        makeFrame({4, 2, 9}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1.5f, 0.25f, 8.0f}, {1, 5, 0});
    const AttributeColumn strain = variableChange(now, before, "strain");
    EXPECT_EQ(strain.name, "strain change");
    EXPECT_EQ(strain.type, ColumnType::Float32);
    ASSERT_EQ(strain.floats.size(), 4u);
    EXPECT_TRUE(std::isnan(strain.floats[0]));
    EXPECT_EQ(strain.floats[1], 0.5f);
    EXPECT_TRUE(std::isnan(strain.floats[2]));
    EXPECT_EQ(strain.floats[3], 0.5f);
    EXPECT_EQ(strain.min, 0.5);
    EXPECT_EQ(strain.max, 0.5);

    const AttributeColumn bonds = variableChange(now, before, "broken_bonds");
    EXPECT_TRUE(std::isnan(bonds.floats[0]));
    EXPECT_EQ(bonds.floats[1], 0.0f);
    EXPECT_EQ(bonds.floats[3], 8.0f);
    EXPECT_EQ(bonds.min, 0.0);
    EXPECT_EQ(bonds.max, 8.0);
}

TEST(FrameDifference, SameIdOrderAndFixedColumns) {
    const Frame now = makeFrame({1, 2}, {3, 1}, {4, 1}, {0, 1}, {0, 0}, {0, 0});
    const Frame before = makeFrame({1, 2}, {0, 1}, {0, 1}, {0, 1}, {0, 0}, {0, 0});
    const AttributeColumn dx = variableChange(now, before, "x");
    EXPECT_EQ(dx.floats, (std::vector<float>{3, 0}));
    const AttributeColumn d = displacementSince(now, before);
    EXPECT_EQ(d.name, "displacement");
    EXPECT_EQ(d.floats, (std::vector<float>{5, 0}));
    EXPECT_EQ(d.min, 0.0);
    EXPECT_EQ(d.max, 5.0);
}

TEST(FrameDifference, MissingVariable) {
    const Frame now = makeFrame({1}, {0}, {0}, {0}, {0}, {0});
    Frame before = makeFrame({1}, {0}, {0}, {0}, {0}, {0});
    before.attributes.pop_back(); // no broken_bonds in the reference
    const AttributeColumn c = variableChange(now, before, "broken_bonds");
    ASSERT_EQ(c.floats.size(), 1u);
    EXPECT_TRUE(std::isnan(c.floats[0]));
    EXPECT_EQ(c.min, 0.0);
    EXPECT_THROW(variableChange(now, before, "porosity"), std::invalid_argument);
}

TEST(FrameDifference, DisplacementAcrossPeriodicBoundaries) {
    Frame before =
        makeFrame({1, 2, 3}, {0.5f, 5, 5}, {5, 5, 9.5f}, {5, 5, 5}, {0, 0, 0}, {0, 0, 0});
    Frame now = makeFrame({3, 1, 2}, {5, 9.5f, 5}, {0.5f, 5, 5}, {5, 5, 5}, {0, 0, 0}, {0, 0, 0});
    before.box.known = true;
    before.box.lo = {0, 0, 0};
    before.box.hi = {10, 10, 10};
    before.box.periodic = {true, false, false};
    // id 1 crossed x (periodic): moved 1. id 3 crossed y (not periodic): moved 9.
    EXPECT_EQ(displacementSince(now, before).floats, (std::vector<float>{9, 1, 0}));
    before.box.periodic = {true, true, false};
    EXPECT_EQ(displacementSince(now, before).floats, (std::vector<float>{1, 1, 0}));

    // A tilted cell (xy = 2): leaving through the top in y re-enters at the bottom shifted by -xy.
    before.box.triclinic = true;
    before.box.xy = 2;
    before.box.periodic = {true, true, true};
    Frame tiltedBefore = makeFrame({1}, {1}, {9.5f}, {5}, {0}, {0});
    tiltedBefore.box = before.box;
    const Frame tiltedNow = makeFrame({1}, {-1}, {0.5f}, {5}, {0}, {0});
    EXPECT_EQ(displacementSince(tiltedNow, tiltedBefore).floats, (std::vector<float>{1}));
}
