#include "ui/render/legend_layout.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace faultline::ui {

namespace {
// "-0.5" with a typographic minus sign.
std::string withMinusSign(const std::string& label) {
    if (!label.empty() && label[0] == '-')
        return "\xE2\x88\x92" + label.substr(1);
    return label;
}
} // namespace

float legendScale(int width, int height, float userScale) {
    // Follow the height, but do not let a very wide and short image get a tall legend, and keep
    // labels legible (at least 11 pixels) on small images.
    const float ref = std::min(float(height), float(width) * 0.75f);
    return std::max(0.8f, ref / 720.0f) * std::max(userScale, 0.1f);
}

LegendLayout layoutLegend(const std::vector<core::LegendTick>& ticks, std::string_view title,
                          const FontAtlas* labelFont, const FontAtlas* titleFont, int width,
                          int height, float scale) {
    LegendLayout out;
    const float s = scale;
    const float margin = std::round(16 * s), pad = std::round(10 * s);
    const float barW = std::round(16 * s), tickLen = std::round(5 * s), gap = std::round(4 * s);
    const float barH = std::round(std::max(80.0f * s, 0.42f * float(height)));
    out.outline = std::max(1.0f, std::round(s));

    std::vector<std::string> labels;
    float labelW = 0;
    for (const core::LegendTick& t : ticks) {
        labels.push_back(withMinusSign(t.label));
        if (labelFont)
            labelW = std::max(labelW, labelFont->measure(labels.back()));
    }
    // A long title ("strain change since frame 10") wraps at the space nearest its middle, so
    // the legend stays a narrow strip instead of reaching over the model.
    std::vector<std::string_view> titleLines;
    if (!title.empty())
        titleLines.push_back(title);
    const float barBlockW = barW + tickLen + gap + std::max(labelW, 3.0f * barW);
    if (titleFont && !title.empty() && titleFont->measure(title) > 1.6f * barBlockW) {
        std::size_t best = std::string_view::npos;
        for (std::size_t k = title.find(' '); k != std::string_view::npos;
             k = title.find(' ', k + 1))
            if (best == std::string_view::npos || std::abs(double(k) - title.size() / 2.0) <
                                                      std::abs(double(best) - title.size() / 2.0))
                best = k;
        if (best != std::string_view::npos)
            titleLines = {title.substr(0, best), title.substr(best + 1)};
    }
    float titleW = 0.0f;
    for (auto line : titleLines)
        titleW = titleFont ? std::max(titleW, titleFont->measure(line)) : 0.0f;
    const float lineH = titleFont ? titleFont->ascent() + titleFont->descent() : 0.0f;
    const float titleH = titleFont ? lineH * float(titleLines.size()) : 0.0f;
    const float labelHalf = labelFont ? 0.5f * (labelFont->ascent() + labelFont->descent()) : 0;

    const float content = std::max(barW + tickLen + gap + labelW, titleW);
    out.panel.x1 = float(width) - margin;
    out.panel.x0 = out.panel.x1 - content - 2 * pad;
    const float blockH = titleH + (titleH > 0 ? gap * 2 : 0) + labelHalf + barH + labelHalf;
    out.panel.y0 = std::round(0.5f * (float(height) - blockH)) - pad;
    out.panel.y1 = out.panel.y0 + blockH + 2 * pad;

    out.bar.x0 = out.panel.x0 + pad;
    out.bar.x1 = out.bar.x0 + barW;
    out.bar.y0 = out.panel.y0 + pad + titleH + (titleH > 0 ? gap * 2 : 0) + labelHalf;
    out.bar.y1 = out.bar.y0 + barH;

    if (titleFont)
        for (std::size_t k = 0; k < titleLines.size(); ++k)
            titleFont->layout(titleLines[k], out.bar.x0,
                              out.panel.y0 + pad + titleFont->ascent() + float(k) * lineH,
                              out.titleGlyphs);
    const float markH = out.outline;
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        const float y = std::round(out.bar.y1 - float(ticks[i].t) * barH);
        out.tickMarks.push_back(
            {out.bar.x1, y - markH * 0.5f, out.bar.x1 + tickLen, y + markH * 0.5f});
        if (labelFont) {
            // Centre the digits' height (about 0.72 of the ascent) on the tick.
            const float baseline = y + 0.36f * labelFont->ascent();
            labelFont->layout(labels[i], out.bar.x1 + tickLen + gap, baseline, out.labelGlyphs);
        }
    }
    return out;
}

namespace {
// `text` shortened with "..." to at most maxWidth pixels (whole UTF-8 characters dropped).
std::string fitText(const FontAtlas& font, std::string text, float maxWidth) {
    if (font.measure(text) <= maxWidth)
        return text;
    while (!text.empty()) {
        std::size_t cut = text.size() - 1;
        while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
            --cut; // continuation byte: back to the character's start
        text.resize(cut);
        if (font.measure(text + "...") <= maxWidth)
            break;
    }
    return text + "...";
}
} // namespace

LegendLayout layoutCategoryLegend(std::span<const LegendEntry> entries, std::string_view title,
                                  const FontAtlas* labelFont, const FontAtlas* titleFont, int width,
                                  int height, float scale) {
    LegendLayout out;
    const float s = scale;
    const float margin = std::round(16 * s), pad = std::round(10 * s), gap = std::round(6 * s);
    out.outline = std::max(1.0f, std::round(s));
    const float labelH = labelFont ? labelFont->ascent() + labelFont->descent() : 14 * s;
    const float rowH = std::round(labelH + 4 * s);
    const float swatch = std::round(0.8f * labelH);
    const float titleH =
        titleFont && !title.empty() ? titleFont->ascent() + titleFont->descent() : 0;

    // Rows that fit in 80% of the height; when some do not, the last row counts the rest.
    const float room = 0.8f * float(height) - 2 * pad - titleH - (titleH > 0 ? gap : 0);
    std::size_t rows = static_cast<std::size_t>(std::max(1.0f, std::floor(room / rowH)));
    std::size_t shown = entries.size();
    std::string more;
    if (entries.size() > rows) {
        shown = rows > 1 ? rows - 1 : 0;
        more = "+ " + std::to_string(entries.size() - shown) + " more";
    }
    std::vector<std::string> names;
    float nameW = 0;
    const float maxName = std::max(40.0f * s, 0.25f * float(width));
    for (std::size_t i = 0; i < shown; ++i) {
        names.push_back(labelFont ? fitText(*labelFont, entries[i].name, maxName)
                                  : entries[i].name);
        if (labelFont)
            nameW = std::max(nameW, labelFont->measure(names.back()));
    }
    if (!more.empty() && labelFont)
        nameW = std::max(nameW, labelFont->measure(more) - swatch - gap);
    const float titleW = titleFont && !title.empty() ? titleFont->measure(title) : 0;
    const float content = std::max(swatch + gap + nameW, titleW);
    const float blockH =
        titleH + (titleH > 0 ? gap : 0) + rowH * float(shown + (more.empty() ? 0 : 1));
    out.panel.x1 = float(width) - margin;
    out.panel.x0 = out.panel.x1 - content - 2 * pad;
    out.panel.y0 = std::round(0.5f * (float(height) - blockH)) - pad;
    out.panel.y1 = out.panel.y0 + blockH + 2 * pad;

    const float x0 = out.panel.x0 + pad;
    float y = out.panel.y0 + pad;
    if (titleH > 0) {
        titleFont->layout(title, x0, y + titleFont->ascent(), out.titleGlyphs);
        y += titleH + gap;
    }
    for (std::size_t i = 0; i < shown; ++i, y += rowH) {
        const float top = std::round(y + 0.5f * (rowH - swatch));
        out.swatches.push_back({x0, top, x0 + swatch, top + swatch});
        out.swatchColors.push_back(entries[i].color);
        if (labelFont)
            labelFont->layout(names[i], x0 + swatch + gap,
                              std::round(y + 0.5f * (rowH - labelH)) + labelFont->ascent(),
                              out.labelGlyphs);
    }
    if (!more.empty() && labelFont)
        labelFont->layout(more, x0, std::round(y + 0.5f * (rowH - labelH)) + labelFont->ascent(),
                          out.labelGlyphs);
    return out;
}

const FontAtlas* sharedFontAtlas(int pixelHeight) {
    static std::mutex mutex;
    static std::map<int, std::unique_ptr<FontAtlas>> fonts;
    const std::lock_guard lock(mutex);
    auto [it, added] = fonts.try_emplace(pixelHeight);
    if (added)
        if (auto atlas = FontAtlas::load(defaultFontPath(), float(pixelHeight)))
            it->second = std::make_unique<FontAtlas>(std::move(*atlas));
    return it->second.get();
}

float legendStripPixels(std::string_view title, core::ValueRange range, bool integerValues,
                        std::span<const LegendEntry> entries, int width, int height,
                        float userScale) {
    const float scale = legendScale(width, height, userScale);
    const FontAtlas* labels = sharedFontAtlas(legendLabelPixels(scale));
    const FontAtlas* titles = sharedFontAtlas(legendTitlePixels(scale));
    const LegendLayout layout =
        entries.empty()
            ? layoutLegend(core::legendTicks(range, 6, integerValues), title, labels, titles, width,
                           height, scale)
            : layoutCategoryLegend(entries, title, labels, titles, width, height, scale);
    // A gap as wide as the legend's margin keeps the model from touching its panel.
    return std::max(0.0f, float(width) - layout.panel.x0 + std::round(16 * scale));
}

} // namespace faultline::ui
