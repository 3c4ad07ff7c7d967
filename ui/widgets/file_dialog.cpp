#include "ui/widgets/file_dialog.hpp"

#include "ui/widgets/item_registry.hpp"

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <system_error>

namespace faultline::ui {

namespace fs = std::filesystem;

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

std::string sizeText(std::uintmax_t bytes) {
    char buf[32];
    if (bytes >= (1ull << 30))
        std::snprintf(buf, sizeof buf, "%.1f GB", bytes / double(1ull << 30));
    else if (bytes >= (1ull << 20))
        std::snprintf(buf, sizeof buf, "%.1f MB", bytes / double(1ull << 20));
    else if (bytes >= 1024)
        std::snprintf(buf, sizeof buf, "%.0f KB", bytes / 1024.0);
    else
        std::snprintf(buf, sizeof buf, "%ju B", bytes);
    return buf;
}

} // namespace

void FileDialog::open(std::string title, Mode mode, std::string purpose,
                      std::vector<std::string> extensions, std::string directory,
                      std::string fileName) {
    m_title = std::move(title);
    m_mode = mode;
    m_purpose = std::move(purpose);
    m_extensions = std::move(extensions);
    std::error_code ec;
    if (directory.empty() || !fs::is_directory(directory, ec))
        directory = fs::current_path(ec).string();
    m_directory = fs::absolute(directory, ec).lexically_normal().string();
    m_directoryInput = m_directory;
    m_fileName = std::move(fileName);
    m_suggested = m_fileName; // replaced, not edited, by the first thing typed
    m_result.clear();
    m_problem.clear();
    m_open = true;
    m_justOpened = true;
    list();
}

namespace {

// The first edit of a suggested name keeps only what was inserted: the new text between what
// the edit left of the suggestion before and after it. user_data: the suggestion (cleared).
struct NameEdit {
    std::string* suggested;
    bool allSelected; // at the start of the frame: typing then replaced the whole text
};

int replaceSuggestion(ImGuiInputTextCallbackData* data) {
    auto* edit = static_cast<NameEdit*>(data->UserData);
    std::string* suggested = edit->suggested;
    if (data->EventFlag != ImGuiInputTextFlags_CallbackEdit || suggested->empty())
        return 0;
    if (edit->allSelected) { // what was typed already replaced the suggestion
        suggested->clear();
        return 0;
    }
    const std::string before = *suggested,
                      now(data->Buf, static_cast<std::size_t>(data->BufTextLen));
    suggested->clear();
    std::size_t head = 0;
    while (head < before.size() && head < now.size() && before[head] == now[head])
        ++head;
    std::size_t tail = 0;
    while (tail < before.size() - head && tail < now.size() - head &&
           before[before.size() - 1 - tail] == now[now.size() - 1 - tail])
        ++tail;
    // Only an insertion into the whole suggestion is replaced by what was inserted; an edit that
    // already replaced it (select all, then type) or deleted from it stands.
    if (now.size() <= before.size() || head + tail < before.size())
        return 0;
    const std::string inserted = now.substr(head, now.size() - before.size());
    data->DeleteChars(0, data->BufTextLen);
    data->InsertChars(0, inserted.c_str());
    return 0;
}

} // namespace

bool FileDialog::matches(const std::string& name) const {
    if (m_allFiles || m_extensions.empty())
        return true;
    return std::any_of(m_extensions.begin(), m_extensions.end(),
                       [&](const std::string& e) { return endsWith(name, e); });
}

void FileDialog::list() {
    m_entries.clear();
    std::error_code ec;
    for (fs::directory_iterator it(m_directory, fs::directory_options::skip_permission_denied, ec),
         end;
         !ec && it != end; it.increment(ec)) {
        Entry e;
        e.name = it->path().filename().string();
        if (e.name.empty() || e.name[0] == '.')
            continue;
        std::error_code ec2;
        e.directory = it->is_directory(ec2);
        if (!e.directory) {
            if (!matches(e.name))
                continue;
            e.size = it->file_size(ec2);
        }
        m_entries.push_back(std::move(e));
    }
    std::sort(m_entries.begin(), m_entries.end(), [](const Entry& a, const Entry& b) {
        if (a.directory != b.directory)
            return a.directory;
        return a.name < b.name;
    });
}

bool FileDialog::accept() {
    if (m_fileName.empty()) {
        m_problem = "Choose or type a file name.";
        return false;
    }
    fs::path p = fs::path(m_fileName).is_absolute() ? fs::path(m_fileName)
                                                    : fs::path(m_directory) / m_fileName;
    std::string s = p.lexically_normal().string();
    std::error_code ec;
    if (fs::is_directory(s, ec)) {
        m_directory = m_directoryInput = s;
        m_fileName.clear();
        list();
        return false;
    }
    if (m_mode == Mode::Save) {
        if (!m_extensions.empty() &&
            !std::any_of(m_extensions.begin(), m_extensions.end(),
                         [&](const std::string& e) { return endsWith(s, e); }))
            s += m_extensions.front();
        if (!fs::is_directory(fs::path(s).parent_path(), ec)) {
            m_problem = "The folder does not exist.";
            return false;
        }
    } else {
        const bool glob = s.find_first_of("*?[%") != std::string::npos;
        if (!glob && !fs::exists(s, ec)) {
            m_problem = "No such file.";
            return false;
        }
    }
    m_result = s;
    m_open = false;
    return true;
}

bool FileDialog::draw(float scale, ItemRegistry* items) {
    if (!m_open)
        return false;
    const char* popupId = "##filedialog";
    if (m_justOpened) {
        ImGui::OpenPopup(popupId);
        m_justOpened = false;
    }
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowSize(
        ImVec2(std::min(760 * scale, display.x * 0.9f), std::min(540 * scale, display.y * 0.85f)),
        ImGuiCond_Appearing);
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    bool accepted = false;
    bool keepOpen = true;
    if (!ImGui::BeginPopupModal(popupId, &keepOpen,
                                ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoTitleBar)) {
        m_open = false;
        return false;
    }
    ImGui::TextUnformatted(m_title.c_str());
    ImGui::Separator();
    if (ImGui::Button("Up")) {
        m_directory = fs::path(m_directory).parent_path().string();
        if (m_directory.empty())
            m_directory = "/";
        m_directoryInput = m_directory;
        list();
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputText("##folder", &m_directoryInput, ImGuiInputTextFlags_EnterReturnsTrue)) {
        std::error_code ec;
        if (fs::is_directory(m_directoryInput, ec)) {
            m_directory = fs::path(m_directoryInput).lexically_normal().string();
            list();
        } else {
            m_problem = "No such folder.";
        }
    }
    const float footer =
        ImGui::GetFrameHeightWithSpacing() * 2 + ImGui::GetStyle().ItemSpacing.y * 2;
    ImGui::BeginChild("##entries", ImVec2(0, -footer), true);
    const float sizeColumn = ImGui::GetContentRegionAvail().x - 90 * scale;
    for (const Entry& e : m_entries) {
        const std::string label = (e.directory ? e.name + "/" : e.name);
        const bool selected = !e.directory && e.name == m_fileName;
        if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
            if (e.directory) {
                if (ImGui::IsMouseDoubleClicked(0)) {
                    m_directory = (fs::path(m_directory) / e.name).string();
                    m_directoryInput = m_directory;
                    list();
                    break;
                }
            } else {
                m_fileName = e.name;
                m_suggested = m_fileName; // a picked name is a suggestion too
                if (ImGui::IsMouseDoubleClicked(0) && accept()) {
                    accepted = true;
                    break;
                }
            }
        }
        if (!e.directory) {
            ImGui::SameLine(sizeColumn);
            ImGui::TextDisabled("%s", sizeText(e.size).c_str());
        }
    }
    if (m_entries.empty())
        ImGui::TextDisabled("(no matching files here)");
    ImGui::EndChild();

    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(m_mode == Mode::Save ? "Save as" : "File");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::IsWindowAppearing())
        ImGui::SetKeyboardFocusHere();
    // The suggested name is selected when the field takes focus, and whatever is typed first
    // replaces it wherever the cursor was (a click into the field puts the cursor in it): a
    // typed path never lands inside "faults.glb".
    NameEdit edit{&m_suggested, false};
    if (const ImGuiInputTextState* st = ImGui::GetInputTextState(ImGui::GetID("##name")))
        edit.allSelected = st->HasSelection() &&
                           std::min(st->Stb.select_start, st->Stb.select_end) == 0 &&
                           std::max(st->Stb.select_start, st->Stb.select_end) >= st->CurLenW;
    const bool enter =
        ImGui::InputText("##name", &m_fileName,
                         ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll |
                             ImGuiInputTextFlags_CallbackEdit,
                         &replaceSuggestion, &edit);
    if (items)
        items->markLastItem("filedialog.name");
    if (enter && !accepted && accept())
        accepted = true;
    if (!m_extensions.empty()) {
        if (ImGui::Checkbox("All files", &m_allFiles))
            list();
        ImGui::SameLine();
        std::string filter;
        for (const auto& e : m_extensions)
            filter += (filter.empty() ? "" : " ") + ("*" + e);
        ImGui::TextDisabled("%s", m_allFiles ? "" : filter.c_str());
        ImGui::SameLine();
    }
    if (!m_problem.empty()) {
        ImGui::TextColored(ImVec4(0.85f, 0.2f, 0.15f, 1), "%s", m_problem.c_str());
        ImGui::SameLine();
    }
    const float buttons = 200 * scale;
    ImGui::SetCursorPosX(
        std::max(ImGui::GetCursorPosX(), ImGui::GetWindowContentRegionMax().x - buttons));
    if (ImGui::Button("Cancel", ImVec2(buttons * 0.48f, 0)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
        m_open = false;
    }
    ImGui::SameLine();
    if (ImGui::Button(m_mode == Mode::Save ? "Save" : "Open", ImVec2(buttons * 0.48f, 0)) &&
        !accepted && accept())
        accepted = true;
    if (items)
        items->markLastItem("filedialog.ok");
    if (!m_open || !keepOpen) {
        m_open = false;
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
    return accepted;
}

} // namespace faultline::ui
