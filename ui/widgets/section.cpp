#include "ui/widgets/section.hpp"

#include <imgui.h>

namespace faultline::ui {

void sectionHeader(const std::string& title) {
    ImGui::TextUnformatted(title.c_str());
    const ImVec2 a = ImGui::GetItemRectMax();
    const float y = (ImGui::GetItemRectMin().y + a.y) * 0.5f;
    const float x0 = a.x + ImGui::GetStyle().ItemSpacing.x;
    const float x1 = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (x1 > x0)
        ImGui::GetWindowDrawList()->AddLine(ImVec2(x0, y), ImVec2(x1, y), ImGui::GetColorU32(ImGuiCol_Separator));
}

void helpMarker(const char* text) {
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

} // namespace faultline::ui
