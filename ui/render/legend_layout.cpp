#include "ui/render/legend_layout.hpp"

#include <algorithm>
#include <cmath>
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
        for (std::size_t k = title.find(' '); k != std::string_view::npos; k = title.find(' ', k + 1))
            if (best == std::string_view::npos ||
                std::abs(double(k) - title.size() / 2.0) < std::abs(double(best) - title.size() / 2.0))
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

} // namespace faultline::ui
