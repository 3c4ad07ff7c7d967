#include "ui/widgets/section.hpp"

#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <cstdarg>
#include <cstdio>

namespace faultline::ui {

void sectionHeader(const std::string& title) {
    textElided(title); // a long fault or box name is shortened, never cut off
    const ImVec2 a = ImGui::GetItemRectMax();
    const float y = (ImGui::GetItemRectMin().y + a.y) * 0.5f;
    const float x0 = a.x + ImGui::GetStyle().ItemSpacing.x;
    const float x1 = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (x1 > x0)
        ImGui::GetWindowDrawList()->AddLine(ImVec2(x0, y), ImVec2(x1, y),
                                            ImGui::GetColorU32(ImGuiCol_Separator));
}

void hint(const char* format, ...) {
    va_list args;
    va_start(args, format);
    char buffer[2048];
    std::vsnprintf(buffer, sizeof buffer, format, args);
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::BeginGroup(); // one item, as the wrapped text was
    textWrappedAtSpaces(buffer);
    ImGui::EndGroup();
    ImGui::PopStyleColor();
    va_end(args);
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

bool beginScrollingTable(const char* id, int columns, int flags, float height) {
    const ImVec2 size(ImGui::GetContentRegionAvail().x, height);
    // With a margin: ImGui rounds the child window's clipped rectangle, and one that keeps under
    // a pixel of it is hidden all the same.
    const ImVec2 at = ImGui::GetCursorScreenPos();
    if (!ImGui::IsRectVisible(ImVec2(at.x + 2, at.y + 2),
                              ImVec2(at.x + size.x - 2, at.y + size.y - 2))) {
        ImGui::Dummy(size);
        return false;
    }
    return ImGui::BeginTable(id, columns, flags, ImVec2(0, height));
}

} // namespace faultline::ui
