#include "core/color/colormap.hpp"
#include "core/color/legend_ticks.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace faultline::core;

TEST(ColorMap, ParsesJournalNames) {
    EXPECT_EQ(parseColorMap("blue-red")->kind, ColorMapKind::BlueRed);
    EXPECT_EQ(parseColorMap("Viridis")->kind, ColorMapKind::Viridis);
    EXPECT_EQ(parseColorMap("diverging")->kind, ColorMapKind::Diverging);
    EXPECT_EQ(parseColorMap("pastel")->kind, ColorMapKind::Pastel);
    EXPECT_EQ(parseColorMap("bands")->kind, ColorMapKind::Bands);
    EXPECT_EQ(parseColorMap("gray")->kind, ColorMapKind::Gray);
    EXPECT_EQ(parseColorMap("Grey")->kind, ColorMapKind::Gray);
    EXPECT_EQ(parseColorMap("bands")->bands, 10);
    EXPECT_EQ(parseColorMap("bands:12")->bands, 12);
    EXPECT_FALSE(parseColorMap("bands:0"));
    EXPECT_FALSE(parseColorMap("bands:x"));
    EXPECT_FALSE(parseColorMap("bands:5000"));
    EXPECT_FALSE(parseColorMap("rainbow"));
    for (const std::string& name : colorMapNames())
        EXPECT_EQ(colorMapName(*parseColorMap(name)), name);
    EXPECT_EQ(colorMapName({ColorMapKind::Bands, 7}), "bands:7");
}

TEST(ColorMap, BlueRedEndsAndMiddle) {
    const ColorMapSpec m{ColorMapKind::BlueRed};
    const glm::vec3 lo = sampleColorMap(m, 0.0), hi = sampleColorMap(m, 1.0);
    EXPECT_GT(lo.b, 0.9f);
    EXPECT_LT(lo.r, 0.1f);
    EXPECT_GT(hi.r, 0.9f);
    EXPECT_LT(hi.b, 0.1f);
    const glm::vec3 mid = sampleColorMap(m, 0.5);
    EXPECT_NEAR(mid.r, 0.5f * (lo.r + hi.r), 1e-6);
    EXPECT_NEAR(mid.b, 0.5f * (lo.b + hi.b), 1e-6);
    // Clamped outside [0, 1]; NaN is grey.
    EXPECT_EQ(sampleColorMap(m, -3.0), lo);
    EXPECT_EQ(sampleColorMap(m, 7.0), hi);
    EXPECT_EQ(sampleColorMap(m, std::nan("")), kNanColor);
}

TEST(ColorMap, ViridisMatchesPublishedStops) {
    const ColorMapSpec m{ColorMapKind::Viridis};
    const glm::vec3 first = sampleColorMap(m, 0.0), mid = sampleColorMap(m, 0.5),
                    last = sampleColorMap(m, 1.0);
    EXPECT_NEAR(first.r * 255, 0x44, 1e-3);
    EXPECT_NEAR(first.b * 255, 0x54, 1e-3);
    EXPECT_NEAR(mid.g * 255, 0x91, 1e-3);
    EXPECT_NEAR(last.r * 255, 0xFD, 1e-3);
    EXPECT_NEAR(last.g * 255, 0xE7, 1e-3);
}

TEST(ColorMap, DivergingIsGreyInTheMiddle) {
    const glm::vec3 mid = sampleColorMap({ColorMapKind::Diverging}, 0.5);
    EXPECT_NEAR(mid.r, mid.g, 1e-6);
    EXPECT_NEAR(mid.g, mid.b, 1e-6);
}

TEST(ColorMap, GrayIsLinearDarkToLight) {
    const ColorMapSpec m{ColorMapKind::Gray};
    const glm::vec3 lo = sampleColorMap(m, 0.0), mid = sampleColorMap(m, 0.5),
                    hi = sampleColorMap(m, 1.0);
    for (const glm::vec3& c : {lo, mid, hi}) {
        EXPECT_EQ(c.r, c.g);
        EXPECT_EQ(c.g, c.b);
    }
    // Dark but not black (shading must still show), light but not white (white backgrounds).
    EXPECT_GT(lo.r, 0.1f);
    EXPECT_LT(lo.r, 0.25f);
    EXPECT_GT(hi.r, 0.85f);
    EXPECT_LT(hi.r, 0.95f);
    EXPECT_NEAR(mid.r, 0.5f * (lo.r + hi.r), 1e-6);
    EXPECT_LT(sampleColorMap(m, 0.3).r, sampleColorMap(m, 0.31).r);
    const ColorMapTexture tex = colorMapTexture(m);
    EXPECT_FALSE(tex.nearest);
    EXPECT_EQ(tex.bandCount, 0);
    EXPECT_EQ(tex.rgba[0], tex.rgba[2]);
    // No value must not pass for a middle value: NaN is tinted here, grey elsewhere.
    const glm::vec3 nan = sampleColorMap(m, std::nan(""));
    EXPECT_EQ(nan, nanColor(m));
    EXPECT_GT(nan.r - nan.b, 0.15f);
    EXPECT_EQ(nanColor({ColorMapKind::Viridis}), kNanColor);
}

TEST(ColorMap, PastelIsNonLinear) {
    const ColorMapSpec m{ColorMapKind::Pastel};
    const glm::vec3 lo = sampleColorMap(m, 0), hi = sampleColorMap(m, 1),
                    q = sampleColorMap(m, 0.25);
    // sqrt(0.25) = 0.5: a quarter of the range is already half way (in linear light).
    EXPECT_GT((q.r - lo.r) / (hi.r - lo.r), 0.5f);
}

TEST(ColorMap, BandsAlternateExactlyByBand) {
    const ColorMapSpec m{ColorMapKind::Bands, 4};
    const glm::vec3 a = sampleColorMap(m, 0.0), b = sampleColorMap(m, 0.25);
    EXPECT_NE(a, b);
    EXPECT_EQ(sampleColorMap(m, 0.2499), a);
    EXPECT_EQ(sampleColorMap(m, 0.5), a);
    EXPECT_EQ(sampleColorMap(m, 0.75), b);
    EXPECT_EQ(sampleColorMap(m, 1.0), b); // the top value belongs to the last band
    const ColorMapTexture tex = colorMapTexture(m);
    EXPECT_EQ(tex.bandCount, 4);
    EXPECT_TRUE(tex.nearest);
    EXPECT_EQ(tex.width, 2);
}

TEST(ColorMap, TableIsRgba8AtEvenSteps) {
    const auto table = colorMapTable({ColorMapKind::BlueRed}, 3);
    ASSERT_EQ(table.size(), 12u);
    const glm::vec3 mid = sampleColorMap({ColorMapKind::BlueRed}, 0.5);
    EXPECT_EQ(table[4], static_cast<std::uint8_t>(std::lround(mid.r * 255)));
    EXPECT_EQ(table[3], 255);
    EXPECT_EQ(table[11], 255);
    const ColorMapTexture tex = colorMapTexture({ColorMapKind::Viridis}, 256);
    EXPECT_EQ(tex.width, 256);
    EXPECT_EQ(tex.rgba.size(), 1024u);
    EXPECT_FALSE(tex.nearest);
    EXPECT_EQ(tex.bandCount, 0);
}

TEST(ColorRange, ModesAndFallbacks) {
    const ValueRange frame{0.1, 0.4}, all{0.0, 0.9}, fixed{0.0, 0.5};
    EXPECT_EQ(resolveColorRange(RangeMode::CurrentFrame, frame, all, fixed), frame);
    EXPECT_EQ(resolveColorRange(RangeMode::AllFrames, frame, all, fixed), all);
    EXPECT_EQ(resolveColorRange(RangeMode::AllFrames, frame, std::nullopt, fixed), frame);
    EXPECT_EQ(resolveColorRange(RangeMode::Fixed, frame, all, fixed), fixed);
    EXPECT_EQ(widenDegenerate({2.0, 2.0}), (ValueRange{1.98, 2.02}));
    EXPECT_EQ(widenDegenerate({0.0, 0.0}), (ValueRange{-0.5, 0.5}));
    EXPECT_EQ(widenDegenerate({3.0, 1.0}), (ValueRange{1.0, 3.0}));
    EXPECT_EQ(widenDegenerate({std::nan(""), 1.0}), (ValueRange{0.0, 1.0}));
    EXPECT_EQ(unite({0, 1}, {-1, 0.5}), (ValueRange{-1, 1}));
    EXPECT_EQ(*parseRangeMode("all"), RangeMode::AllFrames);
    EXPECT_EQ(rangeModeName(RangeMode::Fixed), "fixed");
    EXPECT_EQ(*parseRangeMode("percentile"), RangeMode::Percentile);
    EXPECT_EQ(rangeModeName(RangeMode::Percentile), "percentile");
    EXPECT_EQ(resolveColorRange(RangeMode::Percentile, frame, all, fixed), frame);
    EXPECT_FALSE(parseRangeMode("sometimes"));
}

TEST(LegendTicks, RoundStepsInsideTheRange) {
    const auto ticks = legendTicks({0.0, 0.5}, 6);
    ASSERT_EQ(ticks.size(), 6u);
    EXPECT_EQ(ticks[0].label, "0.0");
    EXPECT_EQ(ticks[1].label, "0.1");
    EXPECT_EQ(ticks[5].label, "0.5");
    EXPECT_DOUBLE_EQ(ticks[5].t, 1.0);

    const auto odd = legendTicks({-0.13, 1.07}, 6);
    ASSERT_EQ(odd.size(), 6u);
    EXPECT_EQ(odd.front().label, "0.0");
    EXPECT_EQ(odd[1].label, "0.2");
    EXPECT_EQ(odd.back().label, "1.0");
    EXPECT_EQ(legendTicks({0.0, 1.0}, 5)[1].label, "0.25");
    EXPECT_NEAR(odd.front().t, 0.13 / 1.2, 1e-12);

    const auto ints = legendTicks({0, 13}, 6);
    ASSERT_EQ(ints.size(), 6u);
    EXPECT_EQ(ints[1].label, "2.5");
    EXPECT_EQ(ints[5].label, "12.5");

    const auto big = legendTicks({0, 2e6}, 5);
    EXPECT_EQ(big[1].label, "5e+05");
    EXPECT_EQ(legendTicks({-1, 1}, 5)[0].label, "-1.0");
    EXPECT_EQ(legendTicks({-1, 1}, 5)[2].label, "0.0");
}

TEST(LegendTicks, NiceStep) {
    EXPECT_DOUBLE_EQ(niceStep({0.0, 1.0}, 6), 0.2);
    EXPECT_DOUBLE_EQ(niceStep({0.0, 13.0}, 6), 2.5);
    EXPECT_DOUBLE_EQ(niceStep({0.0, 100.0}, 3), 50.0);
    EXPECT_DOUBLE_EQ(niceStep({2.0, 2.0}, 5), 1.0);
    EXPECT_DOUBLE_EQ(niceStep({0.0, 12.0}, 6, true), 5.0); // not 2.5
    EXPECT_DOUBLE_EQ(niceStep({0.0, 3.0}, 6, true), 1.0);  // not 0.5
    EXPECT_EQ(legendTicks({0, 12}, 6, true)[1].label, "5");
}

TEST(ColorMap, APaletteMapsCategoryKPlusAHalfToItsColour) {
    ColorMapSpec m{ColorMapKind::Palette, 10, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    EXPECT_EQ(sampleColorMap(m, 0.5 / 3), glm::vec3(1, 0, 0));
    EXPECT_EQ(sampleColorMap(m, 1.5 / 3), glm::vec3(0, 1, 0));
    EXPECT_EQ(sampleColorMap(m, 2.5 / 3), glm::vec3(0, 0, 1));
    const ColorMapTexture tex = colorMapTexture(m);
    EXPECT_EQ(tex.width, 3);
    EXPECT_TRUE(tex.nearest);
    EXPECT_EQ(tex.bandCount, 3);
    EXPECT_EQ(tex.rgba[4 + 1], 255); // the second entry is green
}
