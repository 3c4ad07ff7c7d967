// Text and legend layout: CPU only, no display.
#include "ui/render/legend_layout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace faultline;
using namespace faultline::ui;

namespace {
bool fontAvailable() { return std::ifstream(defaultFontPath()).good(); }
} // namespace

// Without the font these tests cannot lay anything out: skipped, except under the test command
// (FAULTLINE_REQUIRE_GL=1, which installs fonts-dejavu-core), where a skip would hide that no
// legend was measured (issue 39): there they fail, as the GL tests do.
#define FAULTLINE_NEED_FONT()                                                                      \
    do {                                                                                           \
        if (!fontAvailable()) {                                                                    \
            if (const char* required = std::getenv("FAULTLINE_REQUIRE_GL");                        \
                required && *required == '1')                                                      \
                FAIL() << "no font at " << defaultFontPath() << " (the test command needs it)";    \
            GTEST_SKIP() << "no font at " << defaultFontPath();                                    \
        }                                                                                          \
    } while (0)

TEST(TextAtlas, DecodesUtf8) {
    EXPECT_EQ(decodeUtf8("a\xC2\xB5\xE2\x88\x92"), (std::vector<std::uint32_t>{'a', 0xB5, 0x2212}));
    EXPECT_EQ(decodeUtf8("\xFF"), (std::vector<std::uint32_t>{0xFFFD}));
    EXPECT_EQ(decodeUtf8("\xE2\x88"), (std::vector<std::uint32_t>{0xFFFD, 0xFFFD}));
}

TEST(TextAtlas, BakesDejaVuAndLaysOutText) {
    FAULTLINE_NEED_FONT();
    const auto font = FontAtlas::load(defaultFontPath(), 16.0f);
    ASSERT_TRUE(font);
    EXPECT_GT(font->ascent(), 10.0f);
    EXPECT_GT(font->descent(), 2.0f);
    EXPECT_GT(font->measure("strain"), 30.0f);
    EXPECT_GT(font->measure("WWW"), font->measure("iii"));
    std::vector<GlyphQuad> quads;
    font->layout("a b", 10.0f, 20.0f, quads);
    ASSERT_EQ(quads.size(), 2u); // the space has no quad
    EXPECT_LT(quads[0].x1, quads[1].x0);
    EXPECT_EQ(quads[0].x0, std::floor(quads[0].x0)); // snapped to pixels
    EXPECT_LE(quads[0].y1, 20.0f + font->descent() + 1);
    EXPECT_FALSE(FontAtlas::load("/no/such/font.ttf", 16.0f));
}

TEST(LegendLayout, BarTicksAndTextInsideTheImage) {
    const auto ticks = core::legendTicks({0.0, 0.5});
    const float scale = legendScale(1280, 720, 1.0f);
    EXPECT_FLOAT_EQ(scale, 1.0f);
    EXPECT_FLOAT_EQ(legendScale(3840, 2160, 1.0f), 3.0f);
    std::optional<FontAtlas> labels, title;
    if (fontAvailable()) {
        labels = FontAtlas::load(defaultFontPath(), float(legendLabelPixels(scale)));
        title = FontAtlas::load(defaultFontPath(), float(legendTitlePixels(scale)));
    }
    const LegendLayout l = layoutLegend(ticks, "strain", labels ? &*labels : nullptr,
                                        title ? &*title : nullptr, 1280, 720, scale);
    EXPECT_GT(l.bar.y1 - l.bar.y0, 0.4f * 720 - 1);
    EXPECT_EQ(l.tickMarks.size(), ticks.size());
    // The first tick (t = 0) at the bottom of the bar, the last (t = 1) at the top.
    EXPECT_NEAR(0.5f * (l.tickMarks.front().y0 + l.tickMarks.front().y1), l.bar.y1, 1.0f);
    EXPECT_NEAR(0.5f * (l.tickMarks.back().y0 + l.tickMarks.back().y1), l.bar.y0, 1.0f);
    EXPECT_GE(l.panel.x0, 0.0f);
    EXPECT_LE(l.panel.x1, 1280.0f);
    EXPECT_GE(l.panel.y0, 0.0f);
    EXPECT_LE(l.panel.y1, 720.0f);
    if (labels) {
        EXPECT_FALSE(l.labelGlyphs.empty());
        EXPECT_FALSE(l.titleGlyphs.empty());
        for (const GlyphQuad& g : l.labelGlyphs) {
            EXPECT_GE(g.x0, l.panel.x0);
            EXPECT_LE(g.x1, l.panel.x1);
            EXPECT_GE(g.y0, l.panel.y0);
            EXPECT_LE(g.y1, l.panel.y1);
        }
        for (const GlyphQuad& g : l.titleGlyphs)
            EXPECT_LT(g.y1, l.bar.y0); // the title sits above the bar
    }
}

// Issue 41, item 10: colouring by faults has a legend of the faults' names.
TEST(LegendLayout, CategoriesNameEachColourAndSumUpWhatDoesNotFit) {
    FAULTLINE_NEED_FONT();
    const float scale = legendScale(1280, 720, 1.0f);
    const FontAtlas* labels = sharedFontAtlas(legendLabelPixels(scale));
    const FontAtlas* title = sharedFontAtlas(legendTitlePixels(scale));
    ASSERT_TRUE(labels && title);
    std::vector<LegendEntry> few{
        {"Graben W", {1, 0, 0}}, {"Graben E", {0, 0, 1}}, {"no fault", {0.78f, 0.78f, 0.76f}}};
    const LegendLayout l = layoutCategoryLegend(few, "faults", labels, title, 1280, 720, scale);
    ASSERT_EQ(l.swatches.size(), 3u);
    EXPECT_EQ(l.swatchColors[1], glm::vec3(0, 0, 1));
    EXPECT_GT(l.labelGlyphs.size(), 20u); // "Graben W", "Graben E", "no fault"
    EXPECT_FALSE(l.titleGlyphs.empty());
    EXPECT_LT(l.swatches[0].y1, l.swatches[1].y0); // one row each, top to bottom
    EXPECT_GE(l.panel.x0, 0.0f);
    EXPECT_LE(l.panel.x1, 1280.0f);
    for (const LegendRect& r : l.swatches)
        EXPECT_TRUE(r.x0 > l.panel.x0 && r.x1 < l.panel.x1 && r.y0 > l.panel.y0 &&
                    r.y1 < l.panel.y1);
    // The camera fit leaves the legend's strip and a margin's gap.
    EXPECT_FLOAT_EQ(legendStripPixels("faults", {0, 1}, false, few, 1280, 720),
                    1280 - l.panel.x0 + 16);

    // Two hundred faults in a 400-pixel-high image: the rows that fit, then "+ n more".
    std::vector<LegendEntry> many;
    for (int k = 0; k < 200; ++k)
        many.push_back({"C" + std::to_string(k + 1), {0.5f, 0.5f, 0.5f}});
    const float small = legendScale(640, 400, 1.0f);
    const LegendLayout m =
        layoutCategoryLegend(many, "faults", sharedFontAtlas(legendLabelPixels(small)),
                             sharedFontAtlas(legendTitlePixels(small)), 640, 400, small);
    EXPECT_LT(m.swatches.size(), 30u);
    EXPECT_GT(m.swatches.size(), 5u);
    EXPECT_GE(m.panel.y0, 0.0f);
    EXPECT_LE(m.panel.y1, 400.0f);
    // A very long name is shortened: the legend stays a strip at the edge.
    std::vector<LegendEntry> longName{{std::string(200, 'W'), {1, 0, 0}}};
    const LegendLayout n =
        layoutCategoryLegend(longName, "faults", labels, title, 1280, 720, scale);
    EXPECT_LT(n.panel.x1 - n.panel.x0, 0.3f * 1280 + 60);
}

// Issue 41, item 12: a long title's legend is measured, not guessed, for the camera fit.
TEST(LegendLayout, StripWidthFollowsTheTitleAndLabels) {
    FAULTLINE_NEED_FONT();
    const float shortTitle = legendStripPixels("z", {0, 1}, false, {}, 960, 800);
    const float longTitle =
        legendStripPixels("inc_volumetric_strain", {-0.125, 0.125}, false, {}, 960, 800);
    EXPECT_GT(shortTitle, 40.0f);
    EXPECT_GT(longTitle, shortTitle + 40.0f);
}
