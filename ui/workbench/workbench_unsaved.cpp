// Unsaved work: the session's modified state (core::Session::modified) shown as "*" in the title
// and the menu bar; the questions before anything would leave it behind are UnsavedGuard's
// (unsaved_guard.hpp), quitting among them.
#include "ui/workbench/workbench.hpp"

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

void Workbench::requestQuit() {
    guardUnsaved("Quit", [this] { m_quit = true; });
}

std::string Workbench::windowTitle() const {
    const std::string name = m_sessionPath.empty() ? std::string("unsaved session")
                                                   : fs::path(m_sessionPath).filename().string();
    return "Faultline - " + name + (hasUnsavedChanges() ? " *" : "");
}

} // namespace faultline::ui
