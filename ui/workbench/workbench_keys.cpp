// The workbench's keyboard commands (the one table the shortcuts, the menus and the help window
// read) and the shortcut handler.
#include "ui/workbench/workbench.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/session/commands.hpp"

#include <GLFW/glfw3.h> // key codes only (the GLFW back end indexes io.KeysDown by them)
#include <imgui.h>

#include <filesystem>
#include <string_view>

namespace faultline::ui {

namespace fs = std::filesystem;

// Every keyboard command: the keys as the help window and the menus show them, what it does,
// and what it runs. Mouse gestures (no key) are in the help window only. The handler, the help
// and the menus all read this one table, so a shortcut cannot be documented one way and work
// another.
const std::vector<KeyCommand>& Workbench::keyCommands() {
    using W = Workbench;
    static const std::vector<KeyCommand> commands = {
        {"open-data", "Ctrl+O", "Open data", GLFW_KEY_O, true, 0, false,
         [](W& w) { w.openDataDialog(); }},
        {"open-session", "Ctrl+Shift+O", "Open a session", GLFW_KEY_O, true, 1, false,
         [](W& w) {
             w.m_dialog.open("Open a session", FileDialog::Mode::Open, "open-session",
                             {".faultline.json"}, folderOf(w.m_sessionPath));
         }},
        {"save", "Ctrl+S", "Save the session", GLFW_KEY_S, true, 0, false,
         [](W& w) { w.m_sessionPath.empty() ? w.saveSessionAsDialog() : w.saveSession(); }},
        {"save-as", "Ctrl+Shift+S", "Save the session as", GLFW_KEY_S, true, 1, false,
         [](W& w) { w.saveSessionAsDialog(); }},
        // Nothing to undo or redo is said plainly, not as a failure in red (walkthrough).
        {"undo", "Ctrl+Z", "Undo", GLFW_KEY_Z, true, 0, false,
         [](W& w) {
             w.m_session.canUndo() ? w.emit(core::cmd::undo()) : w.info("Nothing to undo");
         }},
        {"redo", "Ctrl+Shift+Z", "Redo", GLFW_KEY_Z, true, 1, false,
         [](W& w) {
             w.m_session.canRedo() ? w.emit(core::cmd::redo()) : w.info("Nothing to redo");
         }},
        {"redo-y", "Ctrl+Y", "Redo", GLFW_KEY_Y, true, -1, false,
         [](W& w) {
             w.m_session.canRedo() ? w.emit(core::cmd::redo()) : w.info("Nothing to redo");
         }},
        {"quit", "Ctrl+Q", "Quit", GLFW_KEY_Q, true, -1, false, [](W& w) { w.requestQuit(); }},
        {"play", "Space", "Play / pause", GLFW_KEY_SPACE, false, -1, false,
         [](W& w) { w.m_playback.playing ? w.pause() : w.play(); }},
        {"previous", "Left", "Previous frame", GLFW_KEY_LEFT, false, 0, true,
         [](W& w) { w.stepFrames(-1); }},
        {"next", "Right", "Next frame", GLFW_KEY_RIGHT, false, 0, true,
         [](W& w) { w.stepFrames(1); }},
        {"back-10", "Shift+Left", "10 frames back", GLFW_KEY_LEFT, false, 1, true,
         [](W& w) { w.stepFrames(-10); }},
        {"forward-10", "Shift+Right", "10 frames on", GLFW_KEY_RIGHT, false, 1, true,
         [](W& w) { w.stepFrames(10); }},
        {"first", "Home", "First frame", GLFW_KEY_HOME, false, -1, false,
         [](W& w) { w.jumpToFrame(0); }},
        {"last", "End", "Last frame", GLFW_KEY_END, false, -1, false,
         [](W& w) {
             w.jumpToFrame(w.dataset() ? static_cast<long long>(w.dataset()->frameCount()) - 1 : 0);
         }},
        {"fit", "F", "Fit the model in the viewports", GLFW_KEY_F, false, -1, false,
         [](W& w) {
             if (w.dataset()) // distance 0: fit the model
                 w.emit(core::cmd::CameraSet("main").distance(0.0));
         }},
        {"screenshot", "F12", "Screenshot of the window (PNG in the working folder)", GLFW_KEY_F12,
         false, -1, false,
         [](W& w) {
             w.requestScreenshot(
                 (fs::current_path() / ("faultline-" + timestampForFile() + ".png")).string());
         }},
        {"help", "F1", "This list", GLFW_KEY_F1, false, -1, false,
         [](W& w) { w.m_help.showKeys = true; }},
        {"tool-rectangle", "R", "Rectangle selection tool", GLFW_KEY_R, false, -1, false,
         [](W& w) { w.m_selection.tool = ViewportTool::Rectangle; }},
        {"tool-lasso", "L", "Lasso selection tool", GLFW_KEY_L, false, -1, false,
         [](W& w) { w.m_selection.tool = ViewportTool::Lasso; }},
        {"tool-orbit", "Esc", "Back to orbiting", GLFW_KEY_ESCAPE, false, -1, false,
         [](W& w) { w.m_selection.tool = ViewportTool::Orbit; }},
        // Mouse gestures: the help window lists them.
        {"", "Left drag in a view", "Orbit"},
        {"", "Right or middle drag, Shift+drag", "Pan"},
        {"", "Wheel", "Zoom"},
        {"", "Ctrl+click a sphere",
         "Add it to the selected fault, or take it out (a new fault when none is selected)"},
        {"", "Drag with a selection tool",
         "Add the visible spheres inside to the selected fault (a new one if none)"},
        {"", "Ctrl+drag / Shift+drag (tool)",
         "Remove them from the selected fault / make a new fault of them"},
        {"", "Click or drag on a metric plot",
         "Go to that frame (Faults panel, metrics over time)"},
        {"", "Drag on a histogram", "Set that variable's threshold (drag the edges to adjust)"},
        {"", "Drag a tab", "Move a panel; drop on an edge to split the area"},
    };
    return commands;
}

const char* Workbench::keysOf(const char* id) {
    for (const KeyCommand& c : keyCommands())
        if (std::string_view(c.id) == id)
            return c.keys;
    return nullptr;
}

void Workbench::runCommand(const char* id) {
    for (const KeyCommand& c : keyCommands())
        if (std::string_view(c.id) == id && c.run) {
            c.run(*this);
            return;
        }
}

void Workbench::handleShortcuts() {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantTextInput || ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId))
        return;
    for (const KeyCommand& c : keyCommands()) {
        if (!c.key || c.ctrl != io.KeyCtrl || (c.shift >= 0 && (c.shift == 1) != io.KeyShift))
            continue;
        if (ImGui::IsKeyPressed(c.key, c.repeat)) {
            c.run(*this);
            return;
        }
    }
}

} // namespace faultline::ui
