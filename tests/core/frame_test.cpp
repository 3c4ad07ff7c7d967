#include "core/model/frame.hpp"
#include "core/selection/column_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace faultline::core;

namespace {
Frame frameWithIds(std::vector<std::int64_t> ids) {
    Frame f;
    f.ids = std::move(ids);
    const std::size_t n = f.ids.size();
    f.x.assign(n, 0);
    f.y.assign(n, 0);
    f.z.assign(n, 0);
    f.radius.assign(n, 1);
    return f;
}
} // namespace

TEST(Frame, DenseIdsMapToRows) {
    Frame f = frameWithIds({10, 12, 11});
    f.finalize();
    EXPECT_EQ(f.rowOf(10), 0u);
    EXPECT_EQ(f.rowOf(11), 2u);
    EXPECT_EQ(f.rowOf(12), 1u);
    EXPECT_FALSE(f.rowOf(13));
    EXPECT_FALSE(f.rowOf(9));
    EXPECT_FALSE(f.rowOf(-5));
}

// rowsOf answers as rowOf does, id by id, on a dense map (ids below its base, past its end,
// the extremes of int64) and on a sparse one.
TEST(Frame, ManyIdsMapToRowsAsOneByOne) {
    const std::vector<std::int64_t> wanted = {10,
                                              12,
                                              11,
                                              13,
                                              9,
                                              -5,
                                              5,
                                              1000000000000LL,
                                              -7,
                                              std::numeric_limits<std::int64_t>::min(),
                                              std::numeric_limits<std::int64_t>::max()};
    for (Frame f : {frameWithIds({10, 12, 11}), frameWithIds({5, 1000000000000LL, -7})}) {
        f.finalize();
        std::vector<std::uint32_t> rows(wanted.size(), 77);
        f.rowsOf(wanted, rows.data());
        for (std::size_t k = 0; k < wanted.size(); ++k) {
            const auto one = f.rowOf(wanted[k]);
            EXPECT_EQ(rows[k], one ? static_cast<std::uint32_t>(*one) : ~std::uint32_t(0))
                << "id " << wanted[k];
        }
    }
}

TEST(Frame, SparseIdsMapToRows) {
    Frame f = frameWithIds({5, 1000000000000LL, -7});
    f.finalize();
    EXPECT_EQ(f.rowOf(1000000000000LL), 1u);
    EXPECT_EQ(f.rowOf(-7), 2u);
    EXPECT_FALSE(f.rowOf(6));
}

TEST(Frame, RepeatedIdIsAnError) {
    Frame f = frameWithIds({1, 2, 1});
    EXPECT_THROW(f.finalize(), std::invalid_argument);
    Frame g = frameWithIds({1, 1000000000000LL, 1});
    EXPECT_THROW(g.finalize(), std::invalid_argument);
}

TEST(Frame, AttributeRangesIgnoreNaN) {
    Frame f = frameWithIds({1, 2, 3});
    f.attributes.push_back(makeAttribute("strain", {0.5f, NAN, -1.0f}, false));
    f.attributes.push_back(makeAttribute("broken", {3, 0, 7}, true));
    f.finalize();
    EXPECT_EQ(f.attribute("strain")->min, -1.0);
    EXPECT_EQ(f.attribute("strain")->max, 0.5);
    ASSERT_TRUE(f.attribute("broken")->isInteger());
    EXPECT_EQ(f.attribute("broken")->max, 7);
}

// The radius range is kept with the frame (views ask for it every UI frame) and skips what is
// not finite, as a scan of the column would.
TEST(Frame, RadiusRangeIsKeptAndIgnoresNaN) {
    Frame f = frameWithIds({1, 2, 3, 4});
    f.radius = {0.5f, NAN, 2.0f, 0.25f};
    f.finalize();
    const auto range = variableRange(f, "radius");
    ASSERT_TRUE(range);
    EXPECT_EQ(range->low, 0.25);
    EXPECT_EQ(range->high, 2.0);
    Frame none = frameWithIds({1});
    none.radius = {NAN};
    none.finalize();
    EXPECT_FALSE(variableRange(none, "radius"));
}

TEST(Frame, IntegralColumnTooLargeForFloatStaysFloat) {
    auto c = makeAttribute("big", {1.0f, 3.0e7f}, true);
    EXPECT_FALSE(c.isInteger());
}

TEST(Frame, MemoryOf525kSpheresWith6ColumnsIsUnder30MB) {
    const std::size_t n = 525000;
    Frame f;
    f.ids.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        f.ids[i] = static_cast<std::int64_t>(i + 1);
    f.x.assign(n, 0);
    f.y.assign(n, 0);
    f.z.assign(n, 0);
    f.radius.assign(n, 1);
    for (int c = 0; c < 6; ++c)
        f.attributes.push_back(
            makeAttribute("c" + std::to_string(c), std::vector<float>(n, 0.5f), false));
    f.finalize();
    EXPECT_LT(f.memoryBytes(), 30u * 1000 * 1000);
}

TEST(Frame, TextColumnsNeedEvidenceToBeIntegers) {
    EXPECT_FALSE(looksLikeIntegerColumn("strain", {0, 0, 0})); // "%g" zeros of a float column
    EXPECT_TRUE(looksLikeIntegerColumn("strain", {0, 1, 0}));
    EXPECT_TRUE(looksLikeIntegerColumn("type", {1, 1})); // LIGGGHTS: one type
    EXPECT_TRUE(looksLikeIntegerColumn("c_broken_bonds", {0, 0}));
    EXPECT_FALSE(looksLikeIntegerColumn("q", {0, 0})); // a charge of zero
}
