#include "core/selection/histogram.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace faultline::core;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

using Counts = std::vector<std::uint64_t>;

Frame frameWith(std::vector<float> values, bool integral, std::string name = "v") {
    Frame f;
    const std::size_t n = values.size();
    for (std::size_t i = 0; i < n; ++i)
        f.ids.push_back(static_cast<std::int64_t>(i));
    f.x.assign(n, 0);
    f.y.assign(n, 0);
    f.z.assign(n, 0);
    f.radius.assign(n, 1);
    f.attributes.push_back(makeAttribute(std::move(name), std::move(values), integral));
    f.finalize();
    return f;
}

ColumnView firstColumn(const Frame& f) { return viewOf(f.attributes.front()); }

HistogramSpec spec(int bins, std::optional<std::array<double, 2>> range = std::nullopt) {
    HistogramSpec s;
    s.bins = bins;
    s.range = range;
    return s;
}

} // namespace

// The journal's {"expect":"histogram","variable":"broken_bonds","of":"visible","bins":13,
// "range":[0,13],...}: equal-width bins over [0, 13), the last bin also holds 13.
TEST(Histogram, JournalSemanticsOnAnIntegerColumn) {
    const Frame f = frameWith({0, 0, 1, 2, 12, 13, 5, 5, 14, -1}, true, "broken_bonds");
    const std::vector<std::uint8_t> mask{1, 0, 1, 1, 0, 1, 1, 0, 1, 0};
    const auto h = computeHistogram(f, "broken_bonds", spec(13, {{0, 13}}), &mask);
    ASSERT_TRUE(h);
    EXPECT_FALSE(h->binning.isInteger());
    EXPECT_EQ(h->binning.bins, 13);
    EXPECT_EQ(h->all.bins, (Counts{2, 1, 1, 0, 0, 2, 0, 0, 0, 0, 0, 0, 2}));
    EXPECT_EQ(h->all.outside, 2u);
    EXPECT_EQ(h->all.nan, 0u);
    ASSERT_TRUE(h->hasVisible);
    EXPECT_EQ(h->visible.bins, (Counts{1, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1}));
    EXPECT_EQ(h->visible.outside, 1u);
    EXPECT_EQ(h->visible.inRange(), 5u);
    EXPECT_EQ(h->edges.size(), 14u);
    EXPECT_EQ(h->edges.front(), 0.0);
    EXPECT_EQ(h->edges.back(), 13.0);
}

TEST(Histogram, ValuesOnEdgesGoRightAndHighIsInTheLastBin) {
    // Float values against edges rounded to float: 0.7f (read from "0.7") opens bin 7 just as
    // the file's 0.7 would; 1.0 is the high end and falls in the last bin.
    const Frame f = frameWith(
        {0.0f, 0.1f, 0.3f, 0.6f, 0.7f, 0.9f, 1.0f, -0.0001f, 1.0001f, kNaN, kInf, -kInf}, false);
    const auto binning = chooseBinning(firstColumn(f), spec(10, {{0, 1}}));
    const Histogram h = computeHistogram(firstColumn(f), binning);
    EXPECT_EQ(h.all.bins, (Counts{1, 1, 0, 1, 0, 0, 1, 1, 0, 2}));
    EXPECT_EQ(h.all.outside, 4u);
    EXPECT_EQ(h.all.nan, 1u);
    EXPECT_FALSE(h.hasVisible);
    EXPECT_TRUE(h.visible.bins.empty());
    EXPECT_EQ(binning.binOf(0.7f), 6);
    EXPECT_EQ(binning.binOf(1.0), 9);
    EXPECT_EQ(binning.binOf(0.0), 0);
    EXPECT_FALSE(binning.binOf(1.0001));
    EXPECT_FALSE(binning.binOf(std::nan("")));
}

TEST(Histogram, IntegerColumnsGetOneBinPerValue) {
    const Frame f = frameWith({3, 5, 5, 7}, true);
    const auto h = computeHistogram(f, "v");
    ASSERT_TRUE(h);
    EXPECT_TRUE(h->binning.isInteger());
    EXPECT_EQ(h->binning.integerWidth, 1);
    EXPECT_EQ(h->binning.lo, 3.0);
    EXPECT_EQ(h->binning.hi, 8.0);
    EXPECT_EQ(h->all.bins, (Counts{1, 0, 2, 0, 1}));
    EXPECT_EQ(h->edges, (std::vector<double>{3, 4, 5, 6, 7, 8}));
}

TEST(Histogram, WideIntegerRangesGroupWholeValues) {
    {
        const Frame f = frameWith({0, 255}, true);
        const auto b = chooseBinning(firstColumn(f));
        EXPECT_EQ(b.bins, 256);
        EXPECT_EQ(b.integerWidth, 1);
    }
    {
        const Frame f = frameWith({0, 256}, true);
        const auto b = chooseBinning(firstColumn(f));
        EXPECT_EQ(b.integerWidth, 2);
        EXPECT_EQ(b.bins, 129);
        EXPECT_EQ(b.hi, 258.0);
    }
    {
        const Frame f = frameWith({0, 1000, 3, 4}, true);
        const auto h = computeHistogram(f, "v");
        ASSERT_TRUE(h);
        EXPECT_EQ(h->binning.integerWidth, 4); // 1001 values, 4 per bin
        EXPECT_EQ(h->binning.bins, 251);
        EXPECT_EQ(h->binning.hi, 1004.0);
        EXPECT_EQ(h->all.bins[0], 2u);   // 0 and 3
        EXPECT_EQ(h->all.bins[1], 1u);   // 4
        EXPECT_EQ(h->all.bins[250], 1u); // 1000
        EXPECT_EQ(h->all.inRange(), 4u);
        EXPECT_EQ(h->edges[1], 4.0);
    }
    {
        const Frame f = frameWith({-10, 5}, true);
        const auto b = chooseBinning(firstColumn(f));
        EXPECT_EQ(b.bins, 16);
        EXPECT_EQ(b.lo, -10.0);
        EXPECT_EQ(b.hi, 6.0);
    }
}

TEST(Histogram, IntegerColumnWithAGivenRange) {
    const Frame f = frameWith({1, 2, 3, 4, 5}, true);
    // Automatic bins: every integer in [1.5, 4] gets a bin.
    const auto h = computeHistogram(f, "v", spec(0, {{1.5, 4}}));
    EXPECT_TRUE(h->binning.isInteger());
    EXPECT_EQ(h->binning.lo, 2.0);
    EXPECT_EQ(h->binning.hi, 5.0);
    EXPECT_EQ(h->all.bins, (Counts{1, 1, 1}));
    EXPECT_EQ(h->all.outside, 2u);
    // A range far beyond int32 is clipped to it (int32 values cannot lie outside).
    const auto wide = chooseBinning(firstColumn(f), spec(0, {{-1e300, 1e300}}));
    EXPECT_EQ(wide.lo, double(std::numeric_limits<std::int32_t>::min()));
    EXPECT_EQ(wide.bins, 256);
    EXPECT_EQ(wide.integerWidth, 16777216); // 2^32 values in 256 bins
    // No integer inside: one equal-width bin over the range.
    const auto g = computeHistogram(f, "v", spec(0, {{2.2, 2.8}}));
    EXPECT_FALSE(g->binning.isInteger());
    EXPECT_EQ(g->all.bins, (Counts{0}));
    EXPECT_EQ(g->all.outside, 5u);
}

TEST(Histogram, IntegerColumnWithGivenBinsSpansMinToMaxPlusOne) {
    const Frame f = frameWith({0, 1, 2, 3}, true);
    const auto h = computeHistogram(f, "v", spec(2));
    EXPECT_FALSE(h->binning.isInteger());
    EXPECT_EQ(h->binning.lo, 0.0);
    EXPECT_EQ(h->binning.hi, 4.0);
    EXPECT_EQ(h->all.bins, (Counts{2, 2}));
}

TEST(Histogram, FreedmanDiaconisByDefault) {
    std::vector<float> values;
    for (int i = 0; i < 100; ++i)
        values.push_back(float(i));
    const Frame f = frameWith(values, false);
    // IQR = 74.25 - 24.75 = 49.5, width = 99 / cbrt(100) = 21.33, (99 - 0) / width = 4.64.
    const auto h = computeHistogram(f, "v");
    EXPECT_FALSE(h->binning.isInteger());
    EXPECT_EQ(h->binning.bins, 5);
    EXPECT_EQ(h->binning.lo, 0.0);
    EXPECT_EQ(h->binning.hi, 99.0);
    EXPECT_EQ(h->all.bins, (Counts{20, 20, 20, 20, 20}));
    // A given range keeps the width: 49.5 / 21.33 = 2.32.
    EXPECT_EQ(chooseBinning(firstColumn(f), spec(0, {{0, 49.5}})).bins, 3);
}

TEST(Histogram, SturgesWhenTheIqrIsZero) {
    std::vector<float> values(99, 0.0f);
    values.push_back(1.0f);
    const Frame f = frameWith(values, false);
    const auto h = computeHistogram(f, "v");
    EXPECT_EQ(h->binning.bins, 8); // ceil(log2 100) + 1
    EXPECT_EQ(h->all.bins, (Counts{99, 0, 0, 0, 0, 0, 0, 1}));
}

TEST(Histogram, AutomaticBinsAreCappedAt256) {
    std::vector<float> values;
    for (int i = 0; i < 1000; ++i)
        values.push_back(float(i) * 1e-3f);
    values.push_back(1000.0f);
    const Frame f = frameWith(values, false);
    EXPECT_EQ(chooseBinning(firstColumn(f)).bins, 256);
}

TEST(Histogram, ConstantColumns) {
    const Frame f = frameWith({2.5f, 2.5f, 2.5f, 2.5f}, false);
    const auto h = computeHistogram(f, "v");
    EXPECT_EQ(h->binning.lo, 2.0);
    EXPECT_EQ(h->binning.hi, 3.0);
    EXPECT_EQ(h->binning.bins, 3); // IQR 0: Sturges, ceil(log2 4) + 1
    EXPECT_EQ(h->all.bins, (Counts{0, 4, 0}));

    const Frame g = frameWith({7, 7}, true);
    const auto hi = computeHistogram(g, "v");
    EXPECT_TRUE(hi->binning.isInteger());
    EXPECT_EQ(hi->all.bins, (Counts{2}));
    EXPECT_EQ(hi->edges, (std::vector<double>{7, 8}));

    // A given range of zero width is widened like numpy's.
    const auto w = computeHistogram(f, "v", spec(2, {{2.5, 2.5}}));
    EXPECT_EQ(w->binning.lo, 2.0);
    EXPECT_EQ(w->binning.hi, 3.0);
    EXPECT_EQ(w->all.bins, (Counts{0, 4}));
}

TEST(Histogram, EmptyAndAllNaNFrames) {
    const Frame empty = frameWith({}, false);
    const auto h = computeHistogram(empty, "v");
    EXPECT_EQ(h->binning.bins, 1);
    EXPECT_EQ(h->binning.lo, -0.5);
    EXPECT_EQ(h->binning.hi, 0.5);
    EXPECT_EQ(h->all.bins, (Counts{0}));
    const std::vector<std::uint8_t> noRows;
    EXPECT_EQ(computeHistogram(empty, "v", {}, &noRows)->visible.bins, (Counts{0}));

    const Frame emptyInt = frameWith({}, true);
    ASSERT_TRUE(emptyInt.attributes.front().isInteger());
    const auto hi = computeHistogram(emptyInt, "v");
    EXPECT_EQ(hi->binning.bins, 1);
    EXPECT_EQ(hi->all.bins, (Counts{0}));

    const Frame nan = frameWith({kNaN, kNaN}, false);
    const std::vector<std::uint8_t> mask{0, 1};
    const auto hn = computeHistogram(nan, "v", {}, &mask);
    EXPECT_EQ(hn->binning.bins, 1);
    EXPECT_EQ(hn->all.bins, (Counts{0}));
    EXPECT_EQ(hn->all.nan, 2u);
    EXPECT_EQ(hn->visible.nan, 1u);
    EXPECT_EQ(hn->all.maxBin(), 0u);
}

TEST(Histogram, IntegerBinningReusedOnAFloatColumn) {
    const Frame ints = frameWith({0, 1, 2}, true);
    const auto binning = chooseBinning(firstColumn(ints));
    ASSERT_TRUE(binning.isInteger());
    const Frame floats = frameWith({0.5f, 2.9f, 3.0f, kNaN, -0.1f}, false);
    const Histogram h = computeHistogram(firstColumn(floats), binning);
    EXPECT_EQ(h.all.bins, (Counts{1, 0, 1}));
    EXPECT_EQ(h.all.outside, 2u);
    EXPECT_EQ(h.all.nan, 1u);
}

TEST(Histogram, BadSpecsAreRejected) {
    const Frame f = frameWith({1, 2}, false);
    EXPECT_THROW(chooseBinning(firstColumn(f), spec(-1)), std::invalid_argument);
    EXPECT_THROW(chooseBinning(firstColumn(f), spec(kMaxHistogramBins + 1)), std::invalid_argument);
    EXPECT_THROW(chooseBinning(firstColumn(f), spec(4, {{1, 0}})), std::invalid_argument);
    EXPECT_THROW(chooseBinning(firstColumn(f), spec(4, {{std::nan(""), 1}})),
                 std::invalid_argument);
    EXPECT_THROW(chooseBinning(firstColumn(f), spec(4, {{-1e308, 1e308}})), std::invalid_argument);
    EXPECT_EQ(chooseBinning(firstColumn(f), spec(kMaxHistogramBins)).bins, kMaxHistogramBins);
}

TEST(Histogram, MissingAndBuiltInVariables) {
    Frame f = frameWith({1, 2, 3}, false);
    EXPECT_FALSE(computeHistogram(f, "nothing"));
    f.radius = {0.25f, 0.5f, 0.5f};
    const auto h = computeHistogram(f, "radius", spec(2, {{0, 1}}));
    ASSERT_TRUE(h);
    EXPECT_EQ(h->all.bins, (Counts{1, 2}));
    EXPECT_EQ(h->all.maxBin(), 2u);
}

TEST(Histogram, LogCounts) {
    EXPECT_EQ(logCounts({0, 9, 99}), (std::vector<double>{0.0, 1.0, 2.0}));
}

// Many rows (several parallel chunks) against the per-value specification binOf().
TEST(Histogram, ParallelCountsMatchBinOf) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 2.0f);
    std::uniform_int_distribution<int> ui(-300, 400);
    const int n = 100000;
    std::vector<float> floats(n), ints(n);
    std::vector<std::uint8_t> mask(n);
    for (int i = 0; i < n; ++i) {
        floats[i] = (i % 101 == 0) ? kNaN : u(rng);
        ints[i] = float(ui(rng));
        mask[i] = static_cast<std::uint8_t>(i % 3);
    }
    for (const bool integral : {false, true}) {
        const Frame f = frameWith(integral ? ints : floats, integral);
        for (const HistogramSpec& s : {spec(0), spec(37, {{0, 1}}), spec(256)}) {
            const auto binning = chooseBinning(firstColumn(f), s);
            const Histogram h = computeHistogram(firstColumn(f), binning, &mask);
            Counts all(binning.bins), visible(binning.bins);
            std::uint64_t nan = 0, outside = 0, visibleOutside = 0;
            for (int i = 0; i < n; ++i) {
                const double v = firstColumn(f).value(i);
                if (auto k = binning.binOf(v)) {
                    ++all[*k];
                    visible[*k] += mask[i] != 0;
                } else if (std::isnan(v)) {
                    ++nan;
                } else {
                    ++outside;
                    visibleOutside += mask[i] != 0;
                }
            }
            EXPECT_EQ(h.all.bins, all);
            EXPECT_EQ(h.visible.bins, visible);
            EXPECT_EQ(h.all.nan, nan);
            EXPECT_EQ(h.all.outside, outside);
            EXPECT_EQ(h.visible.outside, visibleOutside);
            EXPECT_EQ(h.all.inRange() + nan + outside, std::uint64_t(n));
        }
    }
}

// The middle view is offered when a few extreme values set the range, not for a long tail or
// a spike at zero (most spheres undamaged), nor for one value.
TEST(Histogram, ExtremesStretchTheAxisOnlyWhenAFewValuesSetTheRange) {
    auto histogram = [](const std::vector<float>& values) {
        AttributeColumn c;
        c.name = "v";
        c.type = ColumnType::Float32;
        c.floats = values;
        const ColumnView view = viewOf(c);
        return computeHistogram(view, chooseBinning(view));
    };
    std::vector<float> values;
    for (int i = 0; i < 398; ++i)
        values.push_back(float(i) / 400.0f);
    std::vector<float> thrown = values;
    thrown.push_back(1000.0f), thrown.push_back(900.0f); // 2 of 400 far out
    EXPECT_TRUE(extremesStretchAxis(histogram(thrown)));
    EXPECT_FALSE(extremesStretchAxis(histogram(values))); // spread evenly
    // Nine in ten at zero and a tail holding the rest: a fair picture as it is.
    std::vector<float> spike(3600, 0.0f);
    for (int i = 0; i < 400; ++i)
        spike.push_back(float(i) / 100.0f);
    EXPECT_FALSE(extremesStretchAxis(histogram(spike)));
    EXPECT_FALSE(extremesStretchAxis(histogram(std::vector<float>(100, 2.5f)))); // one value
    EXPECT_FALSE(extremesStretchAxis(histogram({0.0f, 1000.0f})));               // too few
}
