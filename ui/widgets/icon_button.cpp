#include "ui/widgets/icon_button.hpp"

#include <imgui.h>

namespace faultline::ui {

bool iconButton(const char* id, Icon icon, const char* tooltip) {
    const float s = ImGui::GetFrameHeight();
    const bool clicked = ImGui::Button(id, ImVec2(s * 1.3f, s));
    if (tooltip && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", tooltip);
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    const ImVec2 c((a.x + b.x) * 0.5f, (a.y + b.y) * 0.5f);
    const float r = s * 0.26f;
    const ImU32 col = ImGui::GetColorU32(ImGuiCol_Text);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    auto right = [&](float x) {
        dl->AddTriangleFilled(ImVec2(x - r * 0.8f, c.y - r), ImVec2(x - r * 0.8f, c.y + r),
                              ImVec2(x + r * 0.8f, c.y), col);
    };
    auto left = [&](float x) {
        dl->AddTriangleFilled(ImVec2(x + r * 0.8f, c.y - r), ImVec2(x + r * 0.8f, c.y + r),
                              ImVec2(x - r * 0.8f, c.y), col);
    };
    auto bar = [&](float x) {
        dl->AddRectFilled(ImVec2(x - r * 0.18f, c.y - r), ImVec2(x + r * 0.18f, c.y + r), col);
    };
    switch (icon) {
    case Icon::Play:
        right(c.x + r * 0.1f);
        break;
    case Icon::Pause:
        bar(c.x - r * 0.4f), bar(c.x + r * 0.4f);
        break;
    case Icon::Next:
        right(c.x - r * 0.2f), bar(c.x + r * 0.75f);
        break;
    case Icon::Previous:
        left(c.x + r * 0.2f), bar(c.x - r * 0.75f);
        break;
    case Icon::First:
        bar(c.x - r * 1.0f), left(c.x - r * 0.05f), left(c.x + r * 0.9f);
        break;
    case Icon::Last:
        right(c.x - r * 0.9f), right(c.x + r * 0.05f), bar(c.x + r * 1.0f);
        break;
    }
    return clicked;
}

} // namespace faultline::ui
