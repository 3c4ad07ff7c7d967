// Where the colour-bar legend goes in an image: panel, bar, tick marks and glyph quads for the
// labels and the title. Pure layout (pixels, y down) so it is tested without a display.
#pragma once

#include "core/color/legend_ticks.hpp"
#include "ui/render/text_atlas.hpp"

#include <glm/vec3.hpp>

#include <span>
#include <string>
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
    // A legend of categories (fault names): a colour square per entry, its name beside it.
    std::vector<LegendRect> swatches;
    std::vector<glm::vec3> swatchColors;
};

// One named colour of a categories legend ("Graben W" in its fault's colour).
struct LegendEntry {
    std::string name;
    glm::vec3 color{0.0f};
};

// Size factor of the legend: 1 at 720 pixels high, proportional above (never below 0.8),
// userScale on top.
float legendScale(int width, int height, float userScale);
// Whether an image this size has room for a legend beside the model: a smaller view shows
// none (issue 41: in three views side by side in a 640-pixel window it covered the model and the
// frame label); its header still names the variable.
inline bool roomForLegend(int width, int height) { return width >= 220 && height >= 150; }
inline int legendLabelPixels(float scale) { return static_cast<int>(14.0f * scale + 0.5f); }
inline int legendTitlePixels(float scale) { return static_cast<int>(16.0f * scale + 0.5f); }

// A vertical bar at the right edge, centred vertically, labels right of it, the title above.
// Fonts may be null (no text is laid out then; the bar and ticks still are).
LegendLayout layoutLegend(const std::vector<core::LegendTick>& ticks, std::string_view title,
                          const FontAtlas* labelFont, const FontAtlas* titleFont, int width,
                          int height, float scale);

// A legend of named colours at the right edge, centred vertically, the title above: one row per
// entry, as many as fit in 80% of the height; the rest summed up in a last row "+ 12 more".
// Names wider than a quarter of the image are shortened with "...".
LegendLayout layoutCategoryLegend(std::span<const LegendEntry> entries, std::string_view title,
                                  const FontAtlas* labelFont, const FontAtlas* titleFont, int width,
                                  int height, float scale);

// The font at a pixel height, loaded once per process and shared (thread-safe); null when the
// font file cannot be read. For measuring text where no renderer is at hand (camera fits).
const FontAtlas* sharedFontAtlas(int pixelHeight);

// How many pixels from the image's right edge the legend takes (its margin included), for a
// camera fit that keeps the model beside it: the layout above with the shared fonts. Categories
// when `entries` is not empty, else a colour bar over `range`.
float legendStripPixels(std::string_view title, core::ValueRange range, bool integerValues,
                        std::span<const LegendEntry> entries, int width, int height,
                        float userScale = 1.0f);

} // namespace faultline::ui
