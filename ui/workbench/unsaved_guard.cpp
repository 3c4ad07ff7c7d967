#include "ui/workbench/unsaved_guard.hpp"

#include <imgui.h>

#include <filesystem>
#include <utility>

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

void UnsavedGuard::guard(std::string action, std::function<void()> proceed,
                         const std::string& target) {
    if (!m_host.hasUnsavedChanges()) {
        proceed();
        return;
    }
    bool reopening = false;
    const std::string& sessionPath = m_host.sessionPath();
    if (!target.empty() && !sessionPath.empty()) {
        std::error_code ec;
        const fs::path a = fs::absolute(target, ec).lexically_normal();
        reopening = !ec && (a == fs::path(sessionPath).lexically_normal() ||
                            fs::equivalent(a, sessionPath, ec));
    }
    m_unsaved = Unsaved{std::move(action), std::move(proceed), reopening};
}

void UnsavedGuard::askOverwrite(std::string path, std::vector<std::string> lost,
                                std::function<void()> then) {
    m_overwrite = Overwrite{std::move(path), std::move(lost), std::move(then)};
}

void UnsavedGuard::savedAsPicked(const std::string& path) {
    m_host.saveSessionAs(path, std::exchange(m_afterSaveAs, {}));
}

const std::vector<std::string>& UnsavedGuard::overwriteLoss() const {
    static const std::vector<std::string> none;
    return m_overwrite ? m_overwrite->lost : none;
}

void UnsavedGuard::draw() {
    drawUnsaved();
    drawOverwrite();
}

void UnsavedGuard::drawOverwrite() {
    if (!m_overwrite)
        return;
    if (!beginCentredModal("Replace the file?"))
        return;
    const Overwrite& p = *m_overwrite;
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
        Overwrite taken = std::move(*m_overwrite);
        m_overwrite.reset();
        ImGui::CloseCurrentPopup();
        m_host.writeSession(taken.path, std::move(taken.then));
    }
    m_host.items().markLastItem("overwrite.replace");
    ImGui::SameLine();
    if (ImGui::Button("Save as...")) {
        m_afterSaveAs = std::move(m_overwrite->then);
        m_overwrite.reset();
        ImGui::CloseCurrentPopup();
        m_host.askWhereToSave();
    }
    m_host.items().markLastItem("overwrite.save-as");
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        m_overwrite.reset(); // nothing written, nothing proceeds
        ImGui::CloseCurrentPopup();
        m_host.info("Not saved");
    }
    m_host.items().markLastItem("overwrite.cancel");
    ImGui::EndPopup();
}

void UnsavedGuard::drawUnsaved() {
    if (!m_unsaved)
        return;
    if (!beginCentredModal("Unsaved changes"))
        return;
    const std::string& sessionPath = m_host.sessionPath();
    const bool reopening = m_unsaved->reopening;
    ImGui::Text("%s: the session has changes that are not saved.", m_unsaved->action.c_str());
    ImGui::TextDisabled("%s", sessionPath.empty() ? "It has never been saved."
                              : reopening ? "Reopening its file drops them; Save as keeps them "
                                            "in another file."
                                          : ("Last saved to " + sessionPath).c_str());
    ImGui::Spacing();
    // Reopening the session's own file: Save would write over the file about to be opened.
    const bool saveAs = sessionPath.empty() || reopening;
    if (ImGui::Button(saveAs ? "Save as..." : "Save")) {
        auto proceed = std::move(m_unsaved->proceed);
        m_unsaved.reset();
        ImGui::CloseCurrentPopup();
        if (saveAs) {
            m_afterSaveAs = std::move(proceed);
            m_host.askWhereToSave();
        } else {
            m_host.saveSessionAs(sessionPath, std::move(proceed));
        }
    }
    m_host.items().markLastItem("unsaved.save");
    ImGui::SameLine();
    if (ImGui::Button("Discard changes")) {
        auto proceed = std::move(m_unsaved->proceed);
        m_unsaved.reset();
        ImGui::CloseCurrentPopup();
        proceed();
    }
    m_host.items().markLastItem("unsaved.discard");
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        m_unsaved.reset();
        ImGui::CloseCurrentPopup();
    }
    m_host.items().markLastItem("unsaved.cancel");
    ImGui::EndPopup();
}

} // namespace faultline::ui
