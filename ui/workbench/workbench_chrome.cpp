// The workbench's frame around the panels: the main menu, figures, the prompts and the file
// dialog's answers (the keys: workbench_keys.cpp; StatusBar, HelpWindows their own).
//
// Index of this file:
// [SECTION] Screenshots and figure sizes
// [SECTION] Main menu
// [SECTION] Prompts and file dialogs
#include "ui/workbench/workbench.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/session/commands.hpp"
#include "core/synth/demo_model.hpp"

#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

void Workbench::openDataDialog() {
    m_dialog.open("Open data (a file, or a pattern such as dump.*.gz)", FileDialog::Mode::Open,
                  "open-data", {},
                  folderOf(state().dataPaths.empty() ? std::string() : state().dataPaths.front()));
}

void Workbench::saveSessionAsDialog() {
    m_dialog.open("Save the session as", FileDialog::Mode::Save, "save-session",
                  {".faultline.json"}, folderOf(m_sessionPath), "analysis.faultline.json");
}

//-----------------------------------------------------------------------------
// [SECTION] Screenshots and figure sizes
//-----------------------------------------------------------------------------

void Workbench::screenshotMainView(const std::string& path) {
    // The main view rendered offscreen at its size on screen, as a journal's render: the
    // window's own pixels still held the closing file dialog (issue 41).
    const auto [width, height] = figureSize();
    core::cmd::Render cmd("main", path, width, height);
    if (figureOptions.transparent)
        cmd.transparent(true);
    emit(cmd, [this, path] { info("Saved the main view to " + path); });
}

std::pair<int, int> Workbench::figureSize() const {
    switch (figureOptions.size) {
    case 1:
        return {1920, 1080};
    case 2:
        return {3840, 2160};
    case 3:
        return {std::clamp(figureOptions.width, 16, 7680),
                std::clamp(figureOptions.height, 16, 4320)};
    default:
        return mainViewPixels();
    }
}

std::pair<int, int> Workbench::mainViewPixels() const {
    if (const auto r = m_items.find("view.image.main"))
        return {std::max(16, static_cast<int>(std::lround(r->x1 - r->x0))),
                std::max(16, static_cast<int>(std::lround(r->y1 - r->y0)))};
    return {1280, 720};
}

void Workbench::drawFigureOptions() {
    if (!m_showFigureOptions)
        return;
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Figure of the main view", &m_showFigureOptions,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                         ImGuiWindowFlags_NoCollapse)) {
        FigureOptions& o = figureOptions;
        ImGui::TextUnformatted("The main view as it is now, rendered again at the size asked.");
        const auto [screenW, screenH] = mainViewPixels();
        char label[64];
        std::snprintf(label, sizeof label, "As on screen (%d x %d)", screenW, screenH);
        ImGui::RadioButton(label, &o.size, 0);
        m_items.markLastItem("figure.size.screen");
        ImGui::RadioButton("1920 x 1080", &o.size, 1);
        m_items.markLastItem("figure.size.hd");
        ImGui::SameLine();
        ImGui::RadioButton("3840 x 2160", &o.size, 2);
        m_items.markLastItem("figure.size.4k");
        ImGui::RadioButton("Width", &o.size, 3);
        m_items.markLastItem("figure.size.custom");
        ImGui::SameLine();
        ImGui::PushItemWidth(80 * m_scale);
        if (ImGui::InputInt("##width", &o.width, 0))
            o.size = 3;
        m_items.markLastItem("figure.width");
        ImGui::SameLine();
        ImGui::TextUnformatted("Height");
        ImGui::SameLine();
        if (ImGui::InputInt("##height", &o.height, 0))
            o.size = 3;
        m_items.markLastItem("figure.height");
        ImGui::PopItemWidth();
        o.width = std::clamp(o.width, 16, 7680);
        o.height = std::clamp(o.height, 16, 4320);
        ImGui::Checkbox("Transparent background", &o.transparent);
        m_items.markLastItem("figure.transparent");
        const auto [w, h] = figureSize();
        ImGui::TextDisabled("%d x %d pixels; the camera frames the same part of the model", w, h);
        if (ImGui::Button("Save as...")) {
            m_showFigureOptions = false;
            m_dialog.open("Save the main view as a PNG", FileDialog::Mode::Save, "screenshot",
                          {".png"}, exportFolder(), "faultline-" + timestampForFile() + ".png");
        }
        m_items.markLastItem("figure.save");
        ImGui::SameLine();
        if (ImGui::Button("Cancel"))
            m_showFigureOptions = false;
        m_items.markLastItem("figure.cancel");
    }
    ImGui::End();
}

std::string Workbench::exportFolder() const {
    if (!m_lastExportFolder.empty())
        return m_lastExportFolder;
    if (!m_sessionPath.empty())
        return folderOf(m_sessionPath);
    const std::string data =
        folderOf(state().dataPaths.empty() ? std::string() : state().dataPaths.front());
    // Not the demo's folder among the application's own data (walkthrough of issue 41): the
    // folder the workbench was started in, as for an unsaved session without data.
    std::error_code ec;
    const fs::path demo = fs::weakly_canonical(core::demoModelFolder(), ec);
    if (data.empty() || (!ec && fs::weakly_canonical(data, ec) == demo))
        return fs::current_path(ec).string();
    return data;
}

//-----------------------------------------------------------------------------
// [SECTION] Main menu
//-----------------------------------------------------------------------------

void Workbench::drawMenus() {
    if (!ImGui::BeginMainMenuBar())
        return;
    // Exports open where the last export went, else beside the session file, else the data
    // (issue 41: they opened in the demo's data folder).
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open data...", keysOf("open-data")))
            runCommand("open-data");
        if (ImGui::MenuItem("Open the demo model"))
            guardUnsaved("Open the demo model", [this] { m_opener.openDemo(); });
        if (ImGui::MenuItem("Open session...", keysOf("open-session")))
            runCommand("open-session");
        if (ImGui::BeginMenu("Open recent", !m_settings.recent().empty())) {
            for (const auto& r : m_settings.recent())
                if (ImGui::MenuItem(r.c_str()))
                    guardUnsaved(
                        "Open " + fs::path(r).filename().string(),
                        [this, r] { m_opener.openPath(r); }, r);
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Save session", keysOf("save")))
            runCommand("save");
        if (ImGui::MenuItem("Save session as...", keysOf("save-as")))
            runCommand("save-as");
        if (ImGui::BeginMenu("Export")) {
            const bool faults = !state().faults.empty();
            if (ImGui::MenuItem("Fault members (CSV)...", nullptr, false, faults))
                m_dialog.open("Export fault members as CSV (id,fault)", FileDialog::Mode::Save,
                              "export-faults", {".csv"}, exportFolder(), "faults.csv");
            if (ImGui::MenuItem("Fault metrics (CSV)...", nullptr, false, faults))
                m_dialog.open("Export fault metrics as CSV", FileDialog::Mode::Save,
                              "export-metrics", {".csv"}, exportFolder(), "fault_metrics.csv");
            if (ImGui::MenuItem("Fault tracks through time (CSV)...", nullptr, false, faults))
                m_dialog.open("Export each fault's best-matching candidate per frame as CSV",
                              FileDialog::Mode::Save, "export-tracks", {".csv"}, exportFolder(),
                              "fault_tracks.csv");
            // Surfaces, as the Surfaces panel exports them.
            if (ImGui::BeginMenu("Surface grids (OpenVDB)",
                                 dataset() && !state().surfaces.empty())) {
                for (const auto& st : state().surfaces) {
                    const bool visible = core::isVisibleSpheres(st.fault);
                    const std::string label = visible ? "visible spheres" : st.fault;
                    if (ImGui::MenuItem((label + "...").c_str()))
                        m_dialog.open("Export the density and colour grids of the " +
                                          (visible ? label : st.fault + " surface") + " (OpenVDB)",
                                      FileDialog::Mode::Save, "export-vdb:" + st.fault, {".vdb"},
                                      exportFolder(), (visible ? "visible" : st.fault) + ".vdb");
                }
                ImGui::EndMenu();
            }
            m_items.markLastItem("menu.export.vdb");
            const bool shown = dataset() && !state().shownSurfaces().empty();
            if (ImGui::MenuItem("Shown surfaces (glTF)...", nullptr, false, shown))
                m_dialog.open("Export the shown surfaces as glTF (one node per fault)",
                              FileDialog::Mode::Save, "export-gltf", {".glb", ".gltf"},
                              exportFolder(), "faults.glb");
            m_items.markLastItem("menu.export.gltf");
            if (ImGui::MenuItem("Shown surfaces and their spheres (glTF)...", nullptr, false,
                                shown))
                m_dialog.open("Export the shown surfaces and their spheres as glTF",
                              FileDialog::Mode::Save, "export-gltf+glyphs", {".glb", ".gltf"},
                              exportFolder(), "faults.glb");
            ImGui::Separator();
            if (ImGui::MenuItem("Journal of this session...", nullptr, false,
                                !m_session.journal().empty()))
                m_dialog.open("Export the journal (replay with faultline replay)",
                              FileDialog::Mode::Save, "export-journal", {".jsonl"}, exportFolder(),
                              "analysis.jsonl");
            if (ImGui::MenuItem("Movie (MP4) or frames (PNG)...", nullptr, false,
                                dataset() != nullptr))
                showMovieOptions();
            if (ImGui::MenuItem("Figure of the main view (PNG)..."))
                showFigureOptions();
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Close data", nullptr, false, dataset() != nullptr))
            guardUnsaved("Close the data", [this] { emit(core::cmd::dataClose()); });
        if (ImGui::MenuItem("Quit", keysOf("quit")))
            runCommand("quit");
        ImGui::EndMenu();
    }
    m_items.markLastItem("menu.file");
    if (ImGui::BeginMenu("Edit")) {
        // "Undo: add 279 spheres to F1" (the ### keeps one ImGui id whatever the label says).
        const std::string undoLabel = m_session.undoLabel(), redoLabel = m_session.redoLabel();
        const std::string undoItem =
            (undoLabel.empty() ? "Undo" : "Undo: " + undoLabel) + "###undo";
        const std::string redoItem =
            (redoLabel.empty() ? "Redo" : "Redo: " + redoLabel) + "###redo";
        if (ImGui::MenuItem(undoItem.c_str(), keysOf("undo"), false, m_session.canUndo()))
            runCommand("undo");
        m_items.markLastItem("edit.undo");
        if (ImGui::MenuItem(redoItem.c_str(), keysOf("redo"), false, m_session.canRedo()))
            runCommand("redo");
        m_items.markLastItem("edit.redo");
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::BeginMenu("Panels")) {
            for (auto& p : m_panels) {
                const bool open = m_layout.contains(p->id());
                if (ImGui::MenuItem(p->title(), nullptr, open)) {
                    open ? (void)m_layout.closePanel(p->id()) : m_layout.openPanel(p->id());
                    commitLayout();
                }
            }
            ImGui::EndMenu();
        }
        if (ImGui::MenuItem("Reset layout")) {
            m_layout = DockLayout::defaultLayout();
            commitLayout();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Screenshot", keysOf("screenshot")))
            runCommand("screenshot");
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("Keyboard and mouse", keysOf("help")))
            runCommand("help");
        if (ImGui::MenuItem("About Faultline"))
            m_help.showAbout = true;
        ImGui::EndMenu();
    }
    // The session's name on the right of the menu bar, "*" while changes are unsaved.
    const std::string title =
        (m_sessionPath.empty() ? std::string("unsaved session")
                               : fs::path(m_sessionPath).filename().string()) +
        (hasUnsavedChanges() ? " *" : "");
    const float w = ImGui::CalcTextSize(title.c_str()).x;
    ImGui::SameLine(std::max(ImGui::GetCursorPosX() + 20 * m_scale,
                             ImGui::GetWindowWidth() - w - 16 * m_scale));
    ImGui::TextDisabled("%s", title.c_str());
    ImGui::EndMainMenuBar();
}

//-----------------------------------------------------------------------------
// [SECTION] Prompts and file dialogs
//-----------------------------------------------------------------------------

// Questions that wait for the user: recover a crashed run's session; where moved data went.
void Workbench::drawPrompts() {
    const ImGuiIO& io = ImGui::GetIO();
    const ImGuiWindowFlags flags =
        ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
    if (const auto& pending = m_recovery.pending(); pending && !m_dialog.isOpen()) {
        if (!ImGui::IsPopupOpen("Recover unsaved work?"))
            ImGui::OpenPopup("Recover unsaved work?");
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                                ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        if (ImGui::BeginPopupModal("Recover unsaved work?", nullptr, flags)) {
            ImGui::TextUnformatted("Faultline did not close normally last time.");
            ImGui::Text("Its session was autosaved%s%s.", pending->savedAt.empty() ? "" : " at ",
                        pending->savedAt.c_str());
            ImGui::TextDisabled("%s", pending->sessionPath.c_str());
            if (ImGui::Button("Recover it")) {
                ImGui::CloseCurrentPopup();
                recover();
            }
            mark("recovery.recover");
            ImGui::SameLine();
            if (ImGui::Button("Discard")) {
                ImGui::CloseCurrentPopup();
                discardRecovery();
            }
            mark("recovery.discard");
            ImGui::EndPopup();
        }
    }
    if (m_opener.missingData() && !m_dialog.isOpen() && !m_recovery.pending()) {
        if (!ImGui::IsPopupOpen("Where is the data?"))
            ImGui::OpenPopup("Where is the data?");
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                                ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        if (ImGui::BeginPopupModal("Where is the data?", nullptr, flags)) {
            const auto& md = *m_opener.missingData();
            ImGui::Text("The data of %s is not where it was saved:",
                        fs::path(md.session).filename().string().c_str());
            for (std::size_t k = 0; k < md.paths.size() && k < 4; ++k)
                ImGui::BulletText("%s", md.paths[k].c_str());
            if (md.paths.size() > 4)
                ImGui::BulletText("and %zu more", md.paths.size() - 4);
            ImGui::TextUnformatted(md.paths.size() == 1
                                       ? "Pick the file where it is now."
                                       : "Pick one of its files where they are now (the others are "
                                         "looked for beside it).");
            if (ImGui::Button("Locate...")) {
                ImGui::CloseCurrentPopup();
                m_dialog.open("Where is " + fs::path(md.paths.front()).filename().string() +
                                  " now?",
                              FileDialog::Mode::Open, "relocate-data", {},
                              fs::path(md.session).parent_path().string(),
                              fs::path(md.paths.front()).filename().string());
            }
            mark("relocate.locate");
            ImGui::SameLine();
            if (ImGui::Button("Cancel")) {
                ImGui::CloseCurrentPopup();
                m_opener.forgetMissing();
            }
            ImGui::EndPopup();
        }
    }
}

void Workbench::handleDialog() {
    const bool wasOpen = m_dialog.isOpen();
    const bool accepted = m_dialog.draw(m_scale, &m_items);
    if (!accepted) {
        if (wasOpen && !m_dialog.isOpen() && m_dialog.purpose() == "relocate-data")
            m_opener.forgetMissing(); // cancelled: the session stays closed
        if (wasOpen && !m_dialog.isOpen() && m_dialog.purpose() == "save-session")
            m_unsaved.saveAsCancelled(); // nothing the question held back proceeds
        return;
    }
    const std::string& purpose = m_dialog.purpose();
    const std::string path = m_dialog.path();
    if (purpose.rfind("export", 0) == 0 || purpose == "screenshot")
        m_lastExportFolder = fs::path(path).parent_path().string();
    if (purpose == "open-data")
        guardUnsaved("Open " + fs::path(path).filename().string(),
                     [this, path] { m_opener.openData({path}); });
    else if (purpose == "open-session")
        guardUnsaved(
            "Open " + fs::path(path).filename().string(),
            [this, path] { m_opener.openSession(path); }, path);
    else if (purpose == "save-session")
        m_unsaved.savedAsPicked(path);
    else if (purpose == "relocate-data")
        m_opener.relocate(path);
    else if (purpose == "screenshot")
        screenshotMainView(path);
    else if (purpose == "export-movie")
        exportMovie(path);
    else if (purpose == "export-faults")
        emit(core::cmd::exportCsv("faults", path));
    else if (purpose.rfind("export-vdb:", 0) == 0)
        m_exports.surfaces({purpose.substr(11)}, path, true, false);
    else if (purpose == "export-gltf" || purpose == "export-gltf+glyphs") {
        const std::vector<std::string> faults = state().shownSurfaces();
        if (faults.empty())
            error("No surface is shown: tick one in the Surfaces panel first");
        else
            m_exports.surfaces(faults, path, false, purpose == "export-gltf+glyphs");
    } else if (purpose == "export-metrics") {
        m_exports.csv(core::cmd::exportCsv("fault_metrics", path));
    } else if (purpose == "export-tracks") {
        m_exports.csv(core::cmd::exportCsv("fault_tracks", path));
    } else if (purpose == "export-journal") {
        std::ofstream out(path);
        for (const auto& cmd : m_session.journal())
            out << cmd.dump() << "\n";
        if (out)
            info("Wrote the journal to " + path);
        else
            error("Cannot write " + path);
    }
}

} // namespace faultline::ui
