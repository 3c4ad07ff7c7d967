#include "ui/widgets/range_slider.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace faultline::ui {

RangeEdit rangeSlider(const char* id, double* lo, double* hi, double min, double max, bool integer,
                      float width, const char* format) {
    RangeEdit edit;
    ImGuiStorage* storage = ImGui::GetStateStorage();
    ImGui::PushID(id);
    const ImGuiID handleKey = ImGui::GetID("##handle");
    const float height = ImGui::GetFrameHeight();
    if (width <= 0)
        width = ImGui::GetContentRegionAvail().x;
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("##range", ImVec2(std::max(width, 20.0f), height));
    const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
    const float grab = std::max(6.0f, height * 0.35f);
    const float x0 = p0.x + grab, x1 = p0.x + width - grab;
    const double span = max > min ? max - min : 1.0;
    auto toX = [&](double v) {
        return x0 + static_cast<float>((std::clamp(v, min, max) - min) / span) * (x1 - x0);
    };
    auto toValue = [&](float x) {
        double v = min + (std::clamp(x, x0, x1) - x0) / std::max(1.0f, x1 - x0) * span;
        return integer ? std::round(v) : v;
    };
    if (ImGui::IsItemActivated()) {
        const float mx = ImGui::GetIO().MousePos.x;
        const float dl = std::fabs(mx - toX(*lo)), dh = std::fabs(mx - toX(*hi));
        storage->SetInt(handleKey, dl < dh || (dl == dh && mx < toX(*lo)) ? 0 : 1);
    }
    if (active) {
        const double v = toValue(ImGui::GetIO().MousePos.x);
        const int h = storage->GetInt(handleKey, 0);
        double nlo = *lo, nhi = *hi;
        if (h == 0)
            nlo = std::min(v, std::clamp(*hi, min, max));
        else
            nhi = std::max(v, std::clamp(*lo, min, max));
        if (nlo != *lo || nhi != *hi) {
            *lo = nlo;
            *hi = nhi;
            edit.changed = true;
        }
    }
    if (ImGui::IsItemDeactivated())
        edit.released = true;

    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float cy = p0.y + height * 0.5f;
    const float rounding = ImGui::GetStyle().FrameRounding;
    dl->AddRectFilled(
        ImVec2(p0.x, p0.y), ImVec2(p0.x + width, p0.y + height),
        ImGui::GetColorU32(hovered || active ? ImGuiCol_FrameBgHovered : ImGuiCol_FrameBg),
        rounding);
    const float a = toX(*lo), b = toX(*hi);
    dl->AddRectFilled(ImVec2(a, cy - height * 0.18f), ImVec2(b, cy + height * 0.18f),
                      ImGui::GetColorU32(ImGuiCol_SliderGrab, 0.55f), 2.0f);
    const ImU32 grabColor =
        ImGui::GetColorU32(active ? ImGuiCol_SliderGrabActive : ImGuiCol_SliderGrab);
    dl->AddRectFilled(ImVec2(a - grab * 0.5f, p0.y + 2), ImVec2(a + grab * 0.5f, p0.y + height - 2),
                      grabColor, 2.0f);
    dl->AddRectFilled(ImVec2(b - grab * 0.5f, p0.y + 2), ImVec2(b + grab * 0.5f, p0.y + height - 2),
                      grabColor, 2.0f);
    char text[96];
    char l[40], h[40];
    std::snprintf(l, sizeof l, format, *lo);
    std::snprintf(h, sizeof h, format, *hi);
    if (*lo <= -1e30)
        std::snprintf(l, sizeof l, "min");
    if (*hi >= 1e30)
        std::snprintf(h, sizeof h, "max");
    std::snprintf(text, sizeof text, "%s  -  %s", l, h);
    const ImVec2 ts = ImGui::CalcTextSize(text);
    dl->AddText(ImVec2(p0.x + (width - ts.x) * 0.5f, p0.y + (height - ts.y) * 0.5f),
                ImGui::GetColorU32(ImGuiCol_Text), text);
    ImGui::PopID();
    return edit;
}

} // namespace faultline::ui
