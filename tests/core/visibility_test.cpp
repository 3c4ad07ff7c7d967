#include "core/selection/row_bits.hpp"
#include "core/selection/visibility.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>

using namespace faultline::core;

namespace {

constexpr float kNaNValue = std::numeric_limits<float>::quiet_NaN();
constexpr float kInfValue = std::numeric_limits<float>::infinity();

struct P {
    float x, y, z;
};

std::shared_ptr<Frame> framePointer(const std::vector<P>& points) {
    auto f = std::make_shared<Frame>();
    for (std::size_t i = 0; i < points.size(); ++i) {
        f->ids.push_back(static_cast<std::int64_t>(i + 1));
        f->x.push_back(points[i].x);
        f->y.push_back(points[i].y);
        f->z.push_back(points[i].z);
        f->radius.push_back(0.5f);
    }
    return f;
}

// Spheres at x = 0, 1, ..., n-1 on the x axis.
std::shared_ptr<Frame> lineFrame(int n) {
    std::vector<P> points;
    for (int i = 0; i < n; ++i)
        points.push_back({float(i), 0.0f, 0.0f});
    auto f = framePointer(points);
    f->finalize();
    return f;
}

CuttingBox box(std::string name, std::array<double, 3> min, std::array<double, 3> max,
               BoxMode mode = BoxMode::Keep, bool enabled = true) {
    CuttingBox b;
    b.name = std::move(name);
    b.min = min;
    b.max = max;
    b.mode = mode;
    b.enabled = enabled;
    return b;
}

// A box over x only (y and z wide open).
CuttingBox xBox(double lo, double hi, BoxMode mode = BoxMode::Keep, bool enabled = true) {
    return box("b", {lo, -1e9, -1e9}, {hi, 1e9, 1e9}, mode, enabled);
}

VariableThreshold threshold(std::string variable, double low, double high, bool enabled = true) {
    VariableThreshold t;
    t.variable = std::move(variable);
    t.low = low;
    t.high = high;
    t.enabled = enabled;
    return t;
}

std::vector<std::uint8_t> bytes(std::initializer_list<int> values) {
    std::vector<std::uint8_t> out;
    for (int v : values)
        out.push_back(static_cast<std::uint8_t>(v));
    return out;
}

// The fused pass, with the invariants every result must hold. Returns the mask.
std::vector<std::uint8_t> visible(const std::shared_ptr<Frame>& frame,
                                  const std::vector<CuttingBox>& boxes,
                                  const std::vector<VariableThreshold>& thresholds = {},
                                  const std::vector<std::uint8_t>* rowMask = nullptr) {
    const VisibilityResult r = computeVisibility(*frame, boxes, thresholds, rowMask);
    EXPECT_EQ(r.mask.size(), frame->size());
    std::size_t ones = 0;
    for (std::uint8_t m : r.mask) {
        EXPECT_TRUE(m == 0 || m == 1);
        ones += m;
    }
    EXPECT_EQ(ones, r.visibleCount);
    return r.mask;
}

} // namespace

TEST(Visibility, NoCriteriaShowsEverything) {
    auto f = lineFrame(5);
    EXPECT_EQ(visible(f, {}), bytes({1, 1, 1, 1, 1}));
}

TEST(Visibility, KeepBoxBoundsAreInclusive) {
    auto f = lineFrame(5);
    EXPECT_EQ(visible(f, {xBox(1, 3)}), bytes({0, 1, 1, 1, 0}));
}

TEST(Visibility, CutBoxBoundsAreInclusive) {
    auto f = lineFrame(5);
    EXPECT_EQ(visible(f, {xBox(1, 3, BoxMode::Cut)}), bytes({1, 0, 0, 0, 1}));
}

TEST(Visibility, KeepMinusCut) {
    auto f = lineFrame(5);
    EXPECT_EQ(visible(f, {xBox(0, 3), xBox(2, 2, BoxMode::Cut)}), bytes({1, 1, 0, 1, 0}));
    // Order of boxes does not matter.
    EXPECT_EQ(visible(f, {xBox(2, 2, BoxMode::Cut), xBox(0, 3)}), bytes({1, 1, 0, 1, 0}));
}

TEST(Visibility, OverlappingKeepBoxesAreAUnion) {
    auto f = lineFrame(6);
    EXPECT_EQ(visible(f, {xBox(0, 2), xBox(1, 3)}), bytes({1, 1, 1, 1, 0, 0}));
    EXPECT_EQ(visible(f, {xBox(0, 0), xBox(5, 5)}), bytes({1, 0, 0, 0, 0, 1}));
}

TEST(Visibility, OverlappingCutBoxes) {
    auto f = lineFrame(6);
    EXPECT_EQ(visible(f, {xBox(0, 2, BoxMode::Cut), xBox(1, 3, BoxMode::Cut)}),
              bytes({0, 0, 0, 0, 1, 1}));
}

TEST(Visibility, DisabledBoxesHaveNoEffect) {
    auto f = lineFrame(4);
    // Only a disabled keep box: no enabled keep box exists, so everything is kept.
    EXPECT_EQ(visible(f, {xBox(0, 0, BoxMode::Keep, false)}), bytes({1, 1, 1, 1}));
    EXPECT_EQ(visible(f, {xBox(-10, 10, BoxMode::Cut, false)}), bytes({1, 1, 1, 1}));
    EXPECT_EQ(visible(f, {xBox(0, 0, BoxMode::Keep, false), xBox(3, 3)}), bytes({0, 0, 0, 1}));
}

TEST(Visibility, BoxIsThreeDimensionalWithCornersInside) {
    const float below = std::nextafter(1.0f, 0.0f);
    const float above = std::nextafter(2.0f, 3.0f);
    auto f = framePointer({{1, 1, 1},
                           {2, 2, 2},
                           {1.5f, 1.5f, 1.5f},
                           {1.5f, below, 1.5f},
                           {1.5f, 1.5f, above},
                           {1, 2, 1}});
    f->finalize();
    EXPECT_EQ(visible(f, {box("c", {1, 1, 1}, {2, 2, 2})}), bytes({1, 1, 1, 0, 0, 1}));
}

TEST(Visibility, BoxBoundsCompareAsTheFileWroteThem) {
    // A centre read from "0.1" is 0.1f (0.100000001490116...); a box bound typed as 0.1 is the
    // same number to the user: the centre lies on the face, inside both boxes.
    const float tenth = 0.1f;
    const float belowTenth = std::nextafter(tenth, 0.0f); // 0.0999999940...
    auto f = framePointer({{tenth, 0, 0}, {belowTenth, 0, 0}});
    f->finalize();
    EXPECT_EQ(visible(f, {xBox(0.1, 1.0)}), bytes({1, 0}));
    EXPECT_EQ(visible(f, {xBox(0.0, 0.1)}), bytes({1, 1}));
    EXPECT_EQ(visible(f, {xBox(double(tenth), double(tenth))}), bytes({1, 0}));
}

TEST(Visibility, EmptyBoxKeepsNothing) {
    auto f = lineFrame(3);
    EXPECT_EQ(visible(f, {xBox(2, 1)}), bytes({0, 0, 0}));
}

TEST(Visibility, ThresholdBoundsAreInclusiveAndNaNNeverPasses) {
    auto f = lineFrame(6);
    f->attributes.push_back(
        makeAttribute("strain", {0.0f, 0.5f, 1.0f, 1.5f, kNaNValue, 2.0f}, false));
    f->finalize();
    EXPECT_EQ(visible(f, {}, {threshold("strain", 0.5, 1.5)}), bytes({0, 1, 1, 1, 0, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("strain", -1e30, 1e30)}), bytes({1, 1, 1, 1, 0, 1}));
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(visible(f, {}, {threshold("strain", -inf, inf)}), bytes({1, 1, 1, 1, 0, 1}));
    EXPECT_EQ(visible(f, {}, {threshold("strain", 1.0, 1.0)}), bytes({0, 0, 1, 0, 0, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("strain", 1.5, 0.5)}), bytes({0, 0, 0, 0, 0, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("strain", std::nan(""), 5)}), bytes({0, 0, 0, 0, 0, 0}));
}

TEST(Visibility, InfiniteValuesPassOnlyInfiniteBounds) {
    auto f = lineFrame(3);
    f->attributes.push_back(makeAttribute("v", {-kInfValue, 0.0f, kInfValue}, false));
    f->finalize();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(visible(f, {}, {threshold("v", -1e300, 1e300)}), bytes({0, 1, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("v", -inf, 0)}), bytes({1, 1, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("v", 0, inf)}), bytes({0, 1, 1}));
    EXPECT_EQ(visible(f, {}, {threshold("v", 1e300, inf)}), bytes({0, 0, 1}));
}

TEST(Visibility, IntegerThresholds) {
    auto f = lineFrame(5);
    f->attributes.push_back(makeAttribute("broken", {0, 1, 2, 3, 4}, true));
    f->finalize();
    ASSERT_TRUE(f->attribute("broken")->isInteger());
    EXPECT_EQ(visible(f, {}, {threshold("broken", 1.5, 3)}), bytes({0, 0, 1, 1, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("broken", 1, 3.9)}), bytes({0, 1, 1, 1, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("broken", -1e30, 1e30)}), bytes({1, 1, 1, 1, 1}));
    EXPECT_EQ(visible(f, {}, {threshold("broken", 1e30, 2e30)}), bytes({0, 0, 0, 0, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("broken", 2.2, 2.8)}), bytes({0, 0, 0, 0, 0}));
    EXPECT_EQ(visible(f, {}, {threshold("broken", 3, 1)}), bytes({0, 0, 0, 0, 0}));
}

TEST(Visibility, ThresholdsAndBoxesAllMustHold) {
    auto f = lineFrame(6);
    f->attributes.push_back(makeAttribute("a", {0, 1, 2, 3, 4, 5}, false));
    f->attributes.push_back(makeAttribute("b", {5, 4, 3, 2, 1, 0}, true));
    f->finalize();
    EXPECT_EQ(visible(f, {}, {threshold("a", 1, 5), threshold("b", 0, 3)}),
              bytes({0, 0, 1, 1, 1, 1}));
    EXPECT_EQ(visible(f, {xBox(0, 4), xBox(3, 3, BoxMode::Cut)},
                      {threshold("a", 1, 5), threshold("b", 0, 3)}),
              bytes({0, 0, 1, 0, 1, 0}));
    // A disabled threshold has no effect.
    EXPECT_EQ(visible(f, {}, {threshold("a", 1, 5), threshold("b", 0, 3, false)}),
              bytes({0, 1, 1, 1, 1, 1}));
}

TEST(Visibility, BuiltInColumnsCanBeThresholded) {
    auto f = framePointer({{0, 0, 0}, {0, 0, 1}, {0, 0, 2}});
    f->radius = {0.1f, 0.2f, 0.3f};
    f->finalize();
    EXPECT_EQ(visible(f, {}, {threshold("z", 1, 2)}), bytes({0, 1, 1}));
    EXPECT_EQ(visible(f, {}, {threshold("radius", 0, 0.2)}), bytes({1, 1, 0})); // 0.2 as written
    EXPECT_EQ(visible(f, {}, {threshold("radius", 0, 0.19)}), bytes({1, 0, 0}));
}

TEST(Visibility, MissingVariableIsIgnoredAndReported) {
    auto f = lineFrame(4);
    f->attributes.push_back(makeAttribute("a", {0, 1, 2, 3}, false));
    f->finalize();
    const std::vector<VariableThreshold> thresholds{threshold("damage", 0, 1), threshold("a", 1, 2),
                                                    threshold("porosity", 0, 1, false),
                                                    threshold("damage", 5, 6)};
    const VisibilityResult r = computeVisibility(*f, {}, thresholds);
    EXPECT_EQ(r.mask, bytes({0, 1, 1, 0}));
    EXPECT_EQ(r.visibleCount, 2u);
    // Enabled ones only, each once, in order.
    EXPECT_EQ(r.missingVariables, std::vector<std::string>{"damage"});
}

TEST(Visibility, RowMaskNonZeroAllows) {
    auto f = lineFrame(5);
    const auto rowMask = bytes({1, 0, 2, 0, 255});
    EXPECT_EQ(visible(f, {}, {}, &rowMask), bytes({1, 0, 1, 0, 1}));
    EXPECT_EQ(visible(f, {xBox(0, 2)}, {}, &rowMask), bytes({1, 0, 1, 0, 0}));
}

TEST(Visibility, EmptyFrame) {
    auto f = lineFrame(0);
    const std::vector<std::uint8_t> rowMask;
    const std::vector<CuttingBox> boxes{xBox(0, 1)};
    const std::vector<VariableThreshold> thresholds{threshold("x", 0, 1), threshold("gone", 0, 1)};
    const VisibilityResult r = computeVisibility(*f, boxes, thresholds, &rowMask);
    EXPECT_TRUE(r.mask.empty());
    EXPECT_EQ(r.visibleCount, 0u);
    EXPECT_EQ(r.missingVariables, std::vector<std::string>{"gone"});
}

// A frame of a few hundred spheres (several words and a partial last word) against a direct
// transcription of the rule in doubles.
TEST(Visibility, MatchesTheRuleOnRandomFrames) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 10.0f);
    std::uniform_int_distribution<int> small(-3, 12);
    for (const int n : {1, 63, 64, 65, 1000, 20000}) {
        std::vector<P> points;
        for (int i = 0; i < n; ++i)
            points.push_back({unit(rng), unit(rng), unit(rng)});
        auto f = framePointer(points);
        std::vector<float> strain(n), broken(n);
        for (int i = 0; i < n; ++i) {
            strain[i] = (i % 17 == 0) ? kNaNValue : unit(rng) / 10.0f;
            broken[i] = float(small(rng));
        }
        f->attributes.push_back(makeAttribute("strain", std::move(strain), false));
        f->attributes.push_back(makeAttribute("broken", std::move(broken), true));
        f->finalize();
        std::vector<std::uint8_t> rowMask(n);
        for (int i = 0; i < n; ++i)
            rowMask[i] = (i % 5 != 0) ? 1 : 0;

        const std::vector<CuttingBox> boxes{
            box("k1", {1, 1, 1}, {6, 9, 9}), box("k2", {5, 0, 0}, {9.5, 5, 5}),
            box("c1", {2, 2, 2}, {4, 4, 4}, BoxMode::Cut),
            box("off", {0, 0, 0}, {10, 10, 10}, BoxMode::Cut, false)};
        const std::vector<VariableThreshold> thresholds{threshold("strain", 0.1, 0.8),
                                                        threshold("broken", 0, 7.5)};
        std::vector<std::uint8_t> expected(n);
        for (int i = 0; i < n; ++i) {
            const double x = f->x[i], y = f->y[i], z = f->z[i];
            bool inKeep = false, inCut = false;
            for (const auto& b : boxes) {
                if (!b.enabled || !b.contains(x, y, z))
                    continue;
                (b.mode == BoxMode::Keep ? inKeep : inCut) = true;
            }
            bool pass = true;
            for (const auto& t : thresholds)
                pass = pass && t.passes(f->attribute(t.variable)->value(i));
            expected[i] = inKeep && !inCut && pass && rowMask[i] != 0;
        }
        EXPECT_EQ(visible(f, boxes, thresholds, &rowMask), expected) << "n = " << n;
    }
}

TEST(RowBits, BoundsRoundToTheNearestFloat) {
    using namespace faultline::core::detail;
    EXPECT_EQ(nearestFloatBound(0.1), 0.1f);
    EXPECT_EQ(nearestFloatBound(-0.1), -0.1f);
    EXPECT_EQ(nearestFloatBound(0.005), 0.005f);
    EXPECT_EQ(nearestFloatBound(2.0), 2.0f);
    EXPECT_EQ(nearestFloatBound(1e300), std::numeric_limits<float>::max());
    EXPECT_EQ(nearestFloatBound(-1e300), -std::numeric_limits<float>::max());
    EXPECT_EQ(nearestFloatBound(std::numeric_limits<double>::infinity()), kInfValue);
    EXPECT_EQ(nearestFloatBound(-std::numeric_limits<double>::infinity()), -kInfValue);
    EXPECT_TRUE(std::isnan(nearestFloatBound(std::nan(""))));
}

TEST(Visibility, ValuesWrittenAsExactlyABoundPass) {
    // A file's 0.005 is stored as the float just below 0.005: it must still pass low = 0.005,
    // and a centre at x = 0.1 must lie inside a box starting at 0.1.
    Frame f;
    f.ids = {1, 2};
    f.x = {0.1f, 0.3f};
    f.y = {0, 0};
    f.z = {0, 0};
    f.radius = {0.005f, 0.01f};
    f.finalize();
    std::vector<VariableThreshold> t{{"radius", 0.005, 0.01, true}};
    EXPECT_EQ(computeVisibility(f, {}, t).visibleCount, 2u);
    std::vector<CuttingBox> keep{{"k", {0.1, -1, -1}, {0.2, 1, 1}, BoxMode::Keep, true}};
    EXPECT_EQ(computeVisibility(f, keep, {}).visibleCount, 1u);
}

TEST(RowBits, IntBounds) {
    using namespace faultline::core::detail;
    EXPECT_EQ(intBoundsFor(1.5, 3.0).lo, 2);
    EXPECT_EQ(intBoundsFor(1.5, 3.9).hi, 3);
    EXPECT_TRUE(intBoundsFor(2.2, 2.8).empty());
    EXPECT_TRUE(intBoundsFor(std::nan(""), 1).empty());
    EXPECT_TRUE(intBoundsFor(3e9, 4e9).empty());
    EXPECT_EQ(intBoundsFor(-1e30, 1e30).lo, std::numeric_limits<std::int32_t>::min());
    EXPECT_EQ(intBoundsFor(-1e30, 1e30).hi, std::numeric_limits<std::int32_t>::max());
}

TEST(RowBits, SimdWordsMatchScalar) {
    using namespace faultline::core::detail;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    std::uniform_int_distribution<int> ui(-5, 5);
    for (int round = 0; round < 200; ++round) {
        float x[64], y[64], z[64];
        std::int32_t ints[64];
        std::uint8_t mask[64];
        for (int j = 0; j < 64; ++j) {
            x[j] = (j % 13 == 0) ? kNaNValue : u(rng);
            y[j] = (j % 29 == 0) ? kInfValue : u(rng);
            z[j] = u(rng);
            ints[j] = ui(rng);
            mask[j] = static_cast<std::uint8_t>(j % 3 == 0 ? 0 : j * 7);
        }
        y[5] = -1.0f; // exactly on a bound
        const float lo = u(rng), hi = u(rng);
        const FloatBox b{{-1, -1, -1}, {1, 1, 1}};
        EXPECT_EQ(inRangeWord(x, 64, lo, hi), scalar::inRangeWord(x, 64, lo, hi));
        EXPECT_EQ(inRangeWord(ints, 64, -2, 3), scalar::inRangeWord(ints, 64, -2, 3));
        EXPECT_EQ(inBoxWord(x, y, z, 64, b), scalar::inBoxWord(x, y, z, 64, b));
        EXPECT_EQ(nonZeroWord(mask, 64), scalar::nonZeroWord(mask, 64));
        const std::uint64_t bits = inBoxWord(x, y, z, 64, b);
        std::uint8_t a[64], s[64];
        expandWord(bits, a, 64);
        scalar::expandWord(bits, s, 64);
        EXPECT_EQ(std::vector<std::uint8_t>(a, a + 64), std::vector<std::uint8_t>(s, s + 64));
    }
}
