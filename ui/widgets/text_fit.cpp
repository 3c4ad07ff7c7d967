#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <algorithm>

namespace faultline::ui {

std::string elided(const std::string& text, float width) {
    if (ImGui::CalcTextSize(text.c_str()).x <= width)
        return text;
    const float dots = ImGui::CalcTextSize("...").x;
    // The longest prefix that fits with the dots (binary search on the byte length; UTF-8
    // continuation bytes are never split off from their lead byte).
    std::size_t lo = 0, hi = text.size();
    while (lo < hi) {
        const std::size_t mid = (lo + hi + 1) / 2;
        if (ImGui::CalcTextSize(text.c_str(), text.c_str() + mid).x + dots <= width)
            lo = mid;
        else
            hi = mid - 1;
    }
    while (lo > 0 && (static_cast<unsigned char>(text[lo]) & 0xC0) == 0x80)
        --lo;
    while (lo > 0 && text[lo - 1] == ' ')
        --lo;
    return text.substr(0, lo) + "...";
}

bool textElided(const std::string& text, float width) {
    if (width <= 0.0f)
        width = ImGui::GetContentRegionAvail().x;
    const std::string shown = elided(text, width);
    ImGui::TextUnformatted(shown.c_str());
    const bool cut = shown != text;
    if (cut && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", text.c_str());
    return cut;
}

std::vector<std::string> wrapAtSpaces(const std::string& text, float width) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string paragraph = text.substr(start, end - start);
        std::string line;
        std::size_t k = 0;
        while (k < paragraph.size()) {
            const std::size_t next = std::min(paragraph.find(' ', k), paragraph.size());
            const std::string word = paragraph.substr(k, next - k);
            const std::string longer = line.empty() ? word : line + " " + word;
            if (!line.empty() && ImGui::CalcTextSize(longer.c_str()).x > width) {
                lines.push_back(line);
                line = word;
            } else {
                line = longer;
            }
            k = next + 1;
        }
        lines.push_back(line);
        start = end + 1;
    }
    return lines;
}

void textWrappedAtSpaces(const std::string& text) {
    const float width = std::max(ImGui::GetContentRegionAvail().x, ImGui::GetFontSize());
    for (const std::string& line : wrapAtSpaces(text, width))
        ImGui::TextUnformatted(line.c_str());
}

void flowSameLine(float width) {
    const float spacing = ImGui::GetStyle().ItemSpacing.x;
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x + spacing + width <= right)
        ImGui::SameLine();
}

float labelledWidth(float fieldWidth, const char* label) {
    return fieldWidth + ImGui::GetStyle().ItemInnerSpacing.x +
           ImGui::CalcTextSize(label, nullptr, true).x;
}

float checkboxWidth(const char* label) { return labelledWidth(ImGui::GetFrameHeight(), label); }

float buttonWidth(const char* label) {
    return ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
}

bool collapsingHeader(const std::string& label, int flags) {
    const ImGuiStyle& style = ImGui::GetStyle();
    // The arrow and the frame's padding on both sides come before and after the label.
    const float room = ImGui::GetContentRegionAvail().x - ImGui::GetFontSize() -
                       style.FramePadding.x * 5 - style.ItemInnerSpacing.x - style.WindowPadding.x;
    const std::string shown = elided(label, room);
    const bool open = ImGui::CollapsingHeader((shown + "###" + label).c_str(), flags);
    if (shown != label && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", label.c_str());
    return open;
}

} // namespace faultline::ui
