#include "ui/workbench/help_windows.hpp"

#include "ui/viewport/view_renderer.hpp"

#include <imgui.h>

#include <algorithm>

namespace faultline::ui {

void HelpWindows::draw(const std::vector<KeyCommand>& keys, float scale,
                       const std::string& journalPath, const ViewRenderer* renderer) {
    const ImGuiIO& io = ImGui::GetIO();
    if (showKeys) {
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                                ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        ImGui::SetNextWindowSize(ImVec2(620 * scale, 0), ImGuiCond_Appearing);
        if (ImGui::Begin("Keyboard and mouse", &showKeys,
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
            if (ImGui::BeginTable("##keys", 2,
                                  ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
                // The keys column as wide as its longest entry; the descriptions wrap.
                float keysWidth = 0.0f;
                for (const auto& s : keys)
                    keysWidth = std::max(keysWidth, ImGui::CalcTextSize(s.keys).x);
                ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, keysWidth);
                ImGui::TableSetupColumn("what", ImGuiTableColumnFlags_WidthStretch);
                for (const auto& s : keys) {
                    ImGui::TableNextRow();
                    ImGui::TableNextColumn();
                    ImGui::TextUnformatted(s.keys);
                    ImGui::TableNextColumn();
                    ImGui::TextWrapped("%s", s.what);
                }
                ImGui::EndTable();
            }
            ImGui::Spacing();
            ImGui::TextWrapped("Every change is a command: Edit > Undo reverts it, and the whole "
                               "run is recorded in %s.",
                               journalPath.empty() ? "the session's journal" : journalPath.c_str());
        }
        ImGui::End();
    }
    if (showAbout) {
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                                ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        if (ImGui::Begin("About Faultline", &showAbout,
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize |
                             ImGuiWindowFlags_NoCollapse)) {
            ImGui::TextUnformatted(
                "Faultline: find, name and follow faults in discrete element models.");
            ImGui::TextDisabled("Dear ImGui %s", IMGUI_VERSION);
            if (renderer)
                ImGui::TextDisabled("%s", renderer->description().c_str());
            if (!journalPath.empty())
                ImGui::TextDisabled("Journal: %s", journalPath.c_str());
        }
        ImGui::End();
    }
}

} // namespace faultline::ui
