#include "core/model/difference_column_cache.hpp"
#include "core/model/frame_difference.hpp"
#include "core/session/color_range.hpp"

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

TEST(DifferenceColumnCache, ComputesOncePerDistinctInputs) {
    auto a =
        std::make_shared<const Frame>(makeFrame({1, 2}, {0, 0}, {0, 0}, {0, 0}, {1, 2}, {0, 1}));
    auto b =
        std::make_shared<const Frame>(makeFrame({2, 1}, {3, 0}, {4, 0}, {0, 0}, {5, 1}, {4, 0}));
    DifferenceColumnCache cache(2);
    auto strain = cache.change(b, a, "strain");
    EXPECT_EQ(strain->floats, (std::vector<float>{3, 0}));
    EXPECT_EQ(cache.change(b, a, "strain"), strain); // the same column, not recomputed
    auto bonds = cache.change(b, a, "broken_bonds");
    EXPECT_NE(bonds, strain);
    EXPECT_EQ(bonds->floats, (std::vector<float>{3, 0}));
    auto moved = cache.displacement(b, a);
    EXPECT_EQ(moved->floats, (std::vector<float>{5, 0}));
    EXPECT_EQ(cache.displacement(b, a), moved);
    EXPECT_NE(cache.change(a, b, "strain"), strain); // the other way round is another column
    // A new frame object with other values is never answered from the cache.
    b = std::make_shared<const Frame>(makeFrame({2, 1}, {0, 0}, {0, 0}, {0, 0}, {7, 1}, {4, 0}));
    EXPECT_EQ(cache.change(b, a, "strain")->floats, (std::vector<float>{5, 0}));
}

// Issue 41: a movie coloured by "change since frame N" got a new range every frame (red meant
// 0 early and +10 late). Over all frames, a change is symmetric about zero, displacement from 0.
TEST(FrameDifference, RangesOverFramesShareOneLegend) {
    // Three frames of two spheres: strain 0, 1, 3 and then -2, so the change since frame 0 runs
    // from -2 to 3 over the frames; the second sphere moves 0.5 per frame.
    std::vector<Frame> frames;
    const float strains[3][2] = {{0, 0}, {1, -2}, {3, 1}};
    for (int t = 0; t < 3; ++t)
        frames.push_back(makeFrame({1, 2}, {0, 0.5f * float(t)}, {0, 0}, {0, 0},
                                   {strains[t][0], strains[t][1]}, {0, 0}));
    auto ds = Dataset::fromLoader(3, [&](std::size_t k) { return frames[k]; });
    ViewState view = mainView();
    view.colorVariable = "strain";
    EXPECT_EQ(differenceRangeOverFrames(*ds, view), std::nullopt); // no difference colouring
    view.difference.mode = ColorDifference::Mode::Change;
    view.difference.reference = {false, 0};
    EXPECT_EQ(differenceRangeOverFrames(*ds, view), (ValueRange{-3, 3}));
    EXPECT_EQ(differenceRangeOverFrames(*ds, view, {1}), (ValueRange{-2, 2}));
    view.difference.mode = ColorDifference::Mode::Displacement;
    EXPECT_EQ(differenceRangeOverFrames(*ds, view), (ValueRange{0, 1}));
    EXPECT_EQ(symmetricAboutZero({0.5, 4}), (ValueRange{-4, 4}));
}

// Issue 41: "this frame's min to max" counted the spheres thresholds hid, so a few hidden
// outliers squeezed the shown spheres into one colour.
TEST(FrameDifference, MaskedRangeCountsOnlyTheRowsShown) {
    const Frame f = makeFrame({1, 2, 3, 4}, {0, 1, 2, 3}, {0, 0, 0, 0}, {0, 0, 0, 0},
                              {0.1f, 0.2f, NAN, 50.0f}, {0, 1, 2, 7});
    const std::vector<std::uint8_t> shown{1, 1, 1, 0};
    EXPECT_EQ(maskedRange(f, "strain", shown), (std::pair<double, double>{0.1f, 0.2f})); // NaN out
    EXPECT_EQ(maskedRange(f, "broken_bonds", shown), (std::pair<double, double>{0, 2}));
    EXPECT_EQ(maskedRange(f, "x", shown), (std::pair<double, double>{0, 2}));
    EXPECT_EQ(maskedRange(f, "strain", {0, 0, 1, 0}), std::nullopt); // only a NaN shown
    EXPECT_EQ(maskedRange(f, "missing", shown), std::nullopt);
    EXPECT_EQ(maskedRange(f, "strain", {1, 1}), std::nullopt); // not a byte per row
}

// The workbench's "1st to 99th percentile" range: strain from motion on a Yade run was 0..92
// over the frame because of a few grains falling out of the model, and every other sphere was
// one colour. 200 spheres 0.0, 0.01, .. 1.99 and two outliers at 90 (one hidden); a NaN.
TEST(FrameDifference, MaskedQuantilesLeaveTheFewExtremesOut) {
    std::vector<std::int64_t> ids;
    std::vector<float> zero, strain;
    std::vector<std::int32_t> bonds;
    for (int i = 0; i < 203; ++i) {
        ids.push_back(i + 1);
        zero.push_back(0);
        strain.push_back(i < 200 ? 0.01f * float(i) : i == 202 ? NAN : 90.0f);
        bonds.push_back(i % 5);
    }
    const Frame f = makeFrame(ids, zero, zero, zero, strain, bonds);
    std::vector<std::uint8_t> shown(203, 1);
    shown[201] = 0;
    // 201 finite values shown (0 .. 1.99 and one 90), sorted indices 0 .. 200: the 1st
    // percentile is index floor(0.01 x 200) = 2, the 99th index ceil(0.99 x 200) = 198.
    EXPECT_EQ(maskedQuantiles(f, "strain", shown, 0.01, 0.99),
              (std::pair<double, double>{strain[2], strain[198]})); // 0.02, 1.98
    EXPECT_EQ(maskedQuantiles(f, "strain", shown, 0, 1), (std::pair<double, double>{0, 90}));
    EXPECT_EQ(maskedQuantiles(f, "broken_bonds", shown, 0.01, 0.99),
              (std::pair<double, double>{0, 4}));
    EXPECT_EQ(maskedQuantiles(f, "missing", shown, 0.01, 0.99), std::nullopt);
    EXPECT_EQ(maskedQuantiles(f, "strain", std::vector<std::uint8_t>(203, 0), 0.01, 0.99),
              std::nullopt);
    EXPECT_EQ(maskedQuantiles(f, "strain", shown, 0.5, 0.5), std::nullopt); // not low < high
    EXPECT_EQ(maskedQuantiles(f, "strain", shown, -0.1, 0.9), std::nullopt);
}
