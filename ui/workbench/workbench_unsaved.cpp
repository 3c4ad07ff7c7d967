// Unsaved work: the session's modified state (core::Session::modified) shown as "*" in the title
// and the menu bar, and a Save / Discard / Cancel question before anything would leave it behind
// (quit, the window's close button, opening a session or other data, closing the data).
#include "ui/workbench/workbench.hpp"

#include <imgui.h>

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

void Workbench::requestQuit() {
    guardUnsaved("Quit", [this] { m_quit = true; });
}

void Workbench::guardUnsaved(std::string action, std::function<void()> proceed) {
    if (!hasUnsavedChanges()) {
        proceed();
        return;
    }
    m_unsavedPrompt = UnsavedPrompt{std::move(action), std::move(proceed)};
}

std::string Workbench::windowTitle() const {
    const std::string name = m_sessionPath.empty() ? std::string("unsaved session")
                                                   : fs::path(m_sessionPath).filename().string();
    return "Faultline - " + name + (hasUnsavedChanges() ? " *" : "");
}

void Workbench::drawUnsavedPrompt() {
    if (!m_unsavedPrompt)
        return;
    const char* id = "Unsaved changes";
    if (!ImGui::IsPopupOpen(id))
        ImGui::OpenPopup(id);
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (!ImGui::BeginPopupModal(
            id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
        return;
    ImGui::Text("%s: the session has changes that are not saved.", m_unsavedPrompt->action.c_str());
    ImGui::TextDisabled("%s", m_sessionPath.empty() ? "It has never been saved."
                                                    : ("Last saved to " + m_sessionPath).c_str());
    ImGui::Spacing();
    if (ImGui::Button(m_sessionPath.empty() ? "Save as..." : "Save")) {
        auto proceed = std::move(m_unsavedPrompt->proceed);
        m_unsavedPrompt.reset();
        ImGui::CloseCurrentPopup();
        if (m_sessionPath.empty()) {
            m_afterSaveAs = std::move(proceed);
            m_dialog.open("Save the session as", FileDialog::Mode::Save, "save-session",
                          {".faultline.json"}, "", "analysis.faultline.json");
        } else {
            saveSessionAs(m_sessionPath, std::move(proceed));
        }
    }
    m_items.markLastItem("unsaved.save");
    ImGui::SameLine();
    if (ImGui::Button("Discard changes")) {
        auto proceed = std::move(m_unsavedPrompt->proceed);
        m_unsavedPrompt.reset();
        ImGui::CloseCurrentPopup();
        proceed();
    }
    m_items.markLastItem("unsaved.discard");
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        m_unsavedPrompt.reset();
        ImGui::CloseCurrentPopup();
    }
    m_items.markLastItem("unsaved.cancel");
    ImGui::EndPopup();
}

} // namespace faultline::ui
