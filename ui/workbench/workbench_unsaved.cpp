// Unsaved work: the session's modified state (core::Session::modified) shown as "*" in the title
// and the menu bar, and a Save / Discard / Cancel question before anything would leave it behind
// (quit, the window's close button, opening a session or other data, closing the data).
#include "ui/workbench/workbench.hpp"

#include <imgui.h>

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

namespace {

// Opens (once) and begins a modal question in the middle of the window; false while hidden.
bool beginCentredModal(const char* id) {
    if (!ImGui::IsPopupOpen(id))
        ImGui::OpenPopup(id);
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    return ImGui::BeginPopupModal(
        id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
}

} // namespace

void Workbench::requestQuit() {
    guardUnsaved("Quit", [this] { m_quit = true; });
}

void Workbench::guardUnsaved(std::string action, std::function<void()> proceed,
                             const std::string& target) {
    if (!hasUnsavedChanges()) {
        proceed();
        return;
    }
    bool reopening = false;
    if (!target.empty() && !m_sessionPath.empty()) {
        std::error_code ec;
        const fs::path a = fs::absolute(target, ec).lexically_normal();
        reopening = !ec && (a == fs::path(m_sessionPath).lexically_normal() ||
                            fs::equivalent(a, m_sessionPath, ec));
    }
    m_unsavedPrompt = UnsavedPrompt{std::move(action), std::move(proceed), reopening};
}

const std::vector<std::string>& Workbench::overwriteLoss() const {
    static const std::vector<std::string> none;
    return m_overwritePrompt ? m_overwritePrompt->lost : none;
}

void Workbench::drawOverwritePrompt() {
    if (!m_overwritePrompt)
        return;
    if (!beginCentredModal("Replace the file?"))
        return;
    const OverwritePrompt& p = *m_overwritePrompt;
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 34.0f);
    ImGui::TextWrapped("%s exists.", p.path.c_str());
    if (p.lost.empty()) {
        ImGui::TextUnformatted("Replace it with this session?");
    } else {
        ImGui::TextUnformatted("It holds what this session does not; replacing it loses:");
        for (const auto& what : p.lost)
            ImGui::BulletText("%s", what.c_str());
    }
    ImGui::PopTextWrapPos();
    ImGui::Spacing();
    if (ImGui::Button("Replace")) {
        OverwritePrompt taken = std::move(*m_overwritePrompt);
        m_overwritePrompt.reset();
        ImGui::CloseCurrentPopup();
        writeSession(taken.path, std::move(taken.then));
    }
    m_items.markLastItem("overwrite.replace");
    ImGui::SameLine();
    if (ImGui::Button("Save as...")) {
        m_afterSaveAs = std::move(m_overwritePrompt->then);
        m_overwritePrompt.reset();
        ImGui::CloseCurrentPopup();
        saveSessionAsDialog();
    }
    m_items.markLastItem("overwrite.save-as");
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        m_overwritePrompt.reset(); // nothing written, nothing proceeds
        ImGui::CloseCurrentPopup();
        info("Not saved");
    }
    m_items.markLastItem("overwrite.cancel");
    ImGui::EndPopup();
}

std::string Workbench::windowTitle() const {
    const std::string name = m_sessionPath.empty() ? std::string("unsaved session")
                                                   : fs::path(m_sessionPath).filename().string();
    return "Faultline - " + name + (hasUnsavedChanges() ? " *" : "");
}

void Workbench::drawUnsavedPrompt() {
    if (!m_unsavedPrompt)
        return;
    if (!beginCentredModal("Unsaved changes"))
        return;
    const bool reopening = m_unsavedPrompt->reopening;
    ImGui::Text("%s: the session has changes that are not saved.", m_unsavedPrompt->action.c_str());
    ImGui::TextDisabled("%s", m_sessionPath.empty() ? "It has never been saved."
                              : reopening ? "Reopening its file drops them; Save as keeps them "
                                            "in another file."
                                          : ("Last saved to " + m_sessionPath).c_str());
    ImGui::Spacing();
    // Reopening the session's own file: Save would write over the file about to be opened.
    const bool saveAs = m_sessionPath.empty() || reopening;
    if (ImGui::Button(saveAs ? "Save as..." : "Save")) {
        auto proceed = std::move(m_unsavedPrompt->proceed);
        m_unsavedPrompt.reset();
        ImGui::CloseCurrentPopup();
        if (saveAs) {
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
