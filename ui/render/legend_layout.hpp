// Where the colour-bar legend goes in an image: panel, bar, tick marks and glyph quads for the
// labels and the title. Pure layout (pixels, y down) so it is tested without a display.
#pragma once

#include "core/color/legend_ticks.hpp"
#include "ui/render/text_atlas.hpp"

#include <string_view>
#include <vector>

namespace faultline::ui {

struct LegendRect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LegendLayout {
    LegendRect panel;                   // soft background behind everything
    LegendRect bar;                     // t = 0 at the bottom edge (y1), t = 1 at the top (y0)
    std::vector<LegendRect> tickMarks;  // short marks right of the bar
    std::vector<GlyphQuad> labelGlyphs; // in the label font's atlas
    std::vector<GlyphQuad> titleGlyphs; // in the title font's atlas
    float outline = 1.0f;               // bar outline width
};

// Size factor of the legend: 1 at 720 pixels high, proportional above (never below 0.8),
// userScale on top.
float legendScale(int width, int height, float userScale);
inline int legendLabelPixels(float scale) { return static_cast<int>(14.0f * scale + 0.5f); }
inline int legendTitlePixels(float scale) { return static_cast<int>(16.0f * scale + 0.5f); }

// A vertical bar at the right edge, centred vertically, labels right of it, the title above.
// Fonts may be null (no text is laid out then; the bar and ticks still are).
LegendLayout layoutLegend(const std::vector<core::LegendTick>& ticks, std::string_view title,
                          const FontAtlas* labelFont, const FontAtlas* titleFont, int width,
                          int height, float scale);

} // namespace faultline::ui
