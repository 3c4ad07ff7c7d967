#include "ui/widgets/series_plot.hpp"

#include "core/color/legend_ticks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace faultline::ui {

namespace {

// Round-number bounds around [lo, hi] and the step between ticks (at most maxTicks of them).
struct Axis {
    double lo = 0, hi = 1, step = 1;
};

Axis niceAxis(double lo, double hi, int maxTicks, bool integer) {
    if (!(hi > lo)) { // one value: a unit (or 10%) band around it
        const double pad = integer ? 1.0 : std::max(std::abs(lo) * 0.1, 1e-6);
        lo -= pad, hi += pad;
    }
    const double step = core::niceStep({lo, hi}, maxTicks, integer);
    return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step, step};
}

std::size_t frameAt(float x, float x0, float x1, std::size_t count) {
    if (count < 2 || x1 <= x0)
        return 0;
    const float t = std::clamp((x - x0) / (x1 - x0), 0.0f, 1.0f);
    return static_cast<std::size_t>(std::lround(t * static_cast<float>(count - 1)));
}

} // namespace

PlotInput seriesPlot(const char* id, std::span<const PlotLine> lines, std::size_t frameCount,
                     std::size_t cursorFrame, ImVec2 size, bool integerValues, float scale,
                     std::span<const PlotMark> marks) {
    PlotInput input;
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(id, size);
    const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float lineH = ImGui::GetTextLineHeight();

    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const PlotLine& l : lines)
        for (double v : l.values)
            if (std::isfinite(v))
                lo = std::min(lo, v), hi = std::max(hi, v);
    const bool haveValues = lo <= hi;
    const int maxYTicks =
        std::clamp(static_cast<int>((size.y - 2.5f * lineH) / (2.2f * lineH)), 2, 6);
    const Axis y = haveValues ? niceAxis(lo, hi, maxYTicks, integerValues) : Axis{};
    std::vector<core::LegendTick> yTicks;
    if (haveValues)
        yTicks = core::legendTicks({y.lo, y.hi}, maxYTicks, integerValues);
    float labelW = ImGui::CalcTextSize("0").x;
    for (const auto& t : yTicks)
        labelW = std::max(labelW, ImGui::CalcTextSize(t.label.c_str()).x);

    // The plot area inside the widget: y labels on the left, frame numbers below.
    const float pad = 6 * scale;
    const float x0 = p0.x + labelW + 2 * pad,
                x1 = p0.x + size.x - pad - ImGui::CalcTextSize("000").x * 0.5f;
    const float y0 = p0.y + lineH * 0.5f, y1 = p0.y + size.y - lineH - pad;
    auto toX = [&](std::size_t f) {
        return frameCount < 2
                   ? 0.5f * (x0 + x1)
                   : x0 + (x1 - x0) * static_cast<float>(f) / static_cast<float>(frameCount - 1);
    };
    auto toY = [&](double v) {
        return y1 - (y1 - y0) * static_cast<float>((v - y.lo) / (y.hi - y.lo));
    };

    const ImU32 grid = ImGui::GetColorU32(ImGuiCol_Border, 0.45f);
    const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text);
    const ImU32 muted = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    dl->AddRectFilled(ImVec2(x0, y0), ImVec2(x1, y1), ImGui::GetColorU32(ImGuiCol_FrameBg));
    for (const auto& t : yTicks) {
        const float yy = toY(t.value);
        dl->AddLine(ImVec2(x0, yy), ImVec2(x1, yy), grid);
        const ImVec2 ts = ImGui::CalcTextSize(t.label.c_str());
        dl->AddText(ImVec2(x0 - pad - ts.x, yy - ts.y * 0.5f), text, t.label.c_str());
    }
    // Frame numbers: whole steps, as many as fit.
    if (frameCount >= 1) {
        const float frameLabelW =
            ImGui::CalcTextSize(std::to_string(frameCount - 1).c_str()).x + 3 * lineH;
        const int maxXTicks = std::max(2, static_cast<int>((x1 - x0) / frameLabelW));
        auto xTicks = frameCount < 2
                          ? std::vector<core::LegendTick>{{0.0, 0.5, "0"}}
                          : core::legendTicks({0.0, double(frameCount - 1)}, maxXTicks, true);
        // The last frame too, where it does not crowd the last round tick.
        const double last = double(frameCount - 1);
        if (!xTicks.empty() && xTicks.back().value < last &&
            toX(frameCount - 1) - toX(static_cast<std::size_t>(xTicks.back().value)) > frameLabelW)
            xTicks.push_back({last, 1.0, std::to_string(frameCount - 1)});
        for (const auto& t : xTicks) {
            const float xx = toX(static_cast<std::size_t>(std::lround(t.value)));
            dl->AddLine(ImVec2(xx, y1), ImVec2(xx, y1 + 3 * scale), muted);
            if (frameCount >= 2)
                dl->AddLine(ImVec2(xx, y0), ImVec2(xx, y1), grid);
            const ImVec2 ts = ImGui::CalcTextSize(t.label.c_str());
            dl->AddText(ImVec2(xx - ts.x * 0.5f, y1 + 3 * scale), text, t.label.c_str());
        }
    }
    dl->AddRect(ImVec2(x0, y0), ImVec2(x1, y1), ImGui::GetColorU32(ImGuiCol_Border));

    dl->PushClipRect(ImVec2(x0 - 4 * scale, y0 - 4 * scale), ImVec2(x1 + 4 * scale, y1 + 4 * scale),
                     true);
    if (haveValues) {
        const bool dots = frameCount > 0 && (x1 - x0) / static_cast<float>(frameCount) > 7 * scale;
        std::vector<ImVec2> run;
        for (const PlotLine& l : lines) {
            auto flush = [&] {
                if (run.size() >= 2)
                    dl->AddPolyline(run.data(), static_cast<int>(run.size()), l.color, 0,
                                    2.0f * scale);
                else if (run.size() == 1)
                    dl->AddCircleFilled(run[0], 2.5f * scale, l.color);
                run.clear();
            };
            for (std::size_t f = 0; f < l.values.size() && f < frameCount; ++f) {
                if (!std::isfinite(l.values[f])) {
                    flush();
                    continue;
                }
                run.emplace_back(toX(f), toY(l.values[f]));
                if (dots)
                    dl->AddCircleFilled(run.back(), 2.2f * scale, l.color);
            }
            flush();
        }
    } else if (!lines.empty()) {
        const char* none = "undefined in every frame";
        const ImVec2 ts = ImGui::CalcTextSize(none);
        dl->AddText(ImVec2(0.5f * (x0 + x1 - ts.x), 0.5f * (y0 + y1 - ts.y)), muted, none);
    }
    dl->PopClipRect();
    // Marks: a dashed line and a letter at the top of the plot. A letter goes in the first row
    // where it overlaps no other (issue 41: marks of neighbouring frames were drawn over each
    // other); past three rows it is left to the tooltip.
    {
        constexpr int kRows = 3;
        std::array<float, kRows> rowEnd;
        rowEnd.fill(-std::numeric_limits<float>::infinity());
        const float letterW = ImGui::CalcTextSize("W").x, rowH = ImGui::GetTextLineHeight();
        for (const PlotMark& m : marks) {
            if (m.frame >= frameCount)
                continue;
            const float xx = toX(m.frame);
            const float dash = 4 * scale;
            for (float yy = y0; yy < y1; yy += 2 * dash)
                dl->AddLine(ImVec2(xx, yy), ImVec2(xx, std::min(y1, yy + dash)), m.color,
                            1.5f * scale);
            // Right of its line, or left of it at the plot's right edge (the last frame's).
            const float left = std::min(xx + 2 * scale, x1 - letterW - 2 * scale);
            for (int row = 0; row < kRows; ++row) {
                const float at = std::max(left, rowEnd[std::size_t(row)]);
                if (at > left + letterW || at + letterW > x1) // too far: try the next row
                    continue;
                const char label[2] = {m.letter, 0};
                const ImVec2 p(at, y0 + 1 * scale + float(row) * rowH);
                // On a patch of the plot's background, so a line through it does not hide it.
                dl->AddRectFilled(
                    ImVec2(p.x - 1 * scale, p.y),
                    ImVec2(p.x + ImGui::CalcTextSize(label).x + 1 * scale, p.y + rowH),
                    ImGui::GetColorU32(ImGuiCol_FrameBg));
                dl->AddText(p, m.color, label);
                rowEnd[std::size_t(row)] = at + letterW;
                break;
            }
        }
    }

    // Input: the frame under the mouse while pressed; the release commits it.
    if (frameCount >= 1 && active)
        input.frame = frameAt(ImGui::GetIO().MousePos.x, x0, x1, frameCount);
    if (frameCount >= 1 && ImGui::IsItemDeactivated()) {
        input.frame = frameAt(ImGui::GetIO().MousePos.x, x0, x1, frameCount);
        input.released = true;
    }

    // The cursor: the frame shown (or being picked).
    if (frameCount >= 1) {
        const std::size_t at = std::min(input.frame.value_or(cursorFrame), frameCount - 1);
        const float xx = toX(at);
        const ImU32 accent = ImGui::GetColorU32(ImGuiCol_SliderGrabActive);
        dl->AddLine(ImVec2(xx, y0), ImVec2(xx, y1), accent, 2.0f * scale);
        const float s = 5 * scale;
        dl->AddTriangleFilled(ImVec2(xx - s, y0 - s * 0.2f), ImVec2(xx + s, y0 - s * 0.2f),
                              ImVec2(xx, y0 + s), accent);
    }
    if (hovered && !active && frameCount >= 1) {
        const std::size_t f = frameAt(ImGui::GetIO().MousePos.x, x0, x1, frameCount);
        ImGui::BeginTooltip();
        ImGui::Text("frame %zu (click or drag to go there)", f);
        for (const PlotLine& l : lines) {
            const double v = f < l.values.size() ? l.values[f] : std::nan("");
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(l.color), "%s", l.label.c_str());
            ImGui::SameLine();
            if (std::isfinite(v))
                ImGui::Text("%.6g", v);
            else
                ImGui::TextDisabled("undefined");
        }
        for (const PlotMark& m : marks)
            if (m.frame == f)
                ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(m.color), "%c %s", m.letter,
                                   m.text.c_str());
        ImGui::EndTooltip();
    }
    return input;
}

} // namespace faultline::ui
