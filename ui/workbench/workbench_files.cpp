// The workbench's session file: saving (asking before writing over another file or losing
// what the file holds), recovering a crashed run's session, screenshot requests, the frame
// memory setting. Opening is DataOpener's, the background exports BackgroundExports'.
#include "ui/workbench/workbench.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/session/commands.hpp"
#include "core/session/save_loss.hpp"

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;

void Workbench::recover() {
    if (const auto path = m_recovery.recover())
        m_opener.openSession(*path);
}

void Workbench::discardRecovery() { m_recovery.discard(); }

void Workbench::askWhereToSave() { saveSessionAsDialog(); }

void Workbench::saveSession() {
    if (m_sessionPath.empty()) {
        askWhereToSave();
        return;
    }
    saveSessionAs(m_sessionPath);
}

void Workbench::saveSessionAs(const std::string& pathIn, std::function<void()> then) {
    const std::string path = absolutePath(pathIn);
    commitLayout(); // active tabs and the like ride along with the save
    std::error_code ec;
    const bool otherFile = path != m_sessionPath && fs::exists(path, ec);
    std::vector<std::string> lost = core::saveLossOverFile(path, state());
    if (otherFile || !lost.empty()) {
        m_unsaved.askOverwrite(path, std::move(lost), std::move(then));
        return;
    }
    writeSession(path, std::move(then));
}

void Workbench::writeSession(const std::string& path, std::function<void()> then) {
    emit(core::cmd::sessionSave(path), [this, path, then] {
        m_sessionPath = path;
        m_settings.addRecent(path);
        info("Saved " + path);
        if (then)
            then();
    });
}

std::optional<std::string> Workbench::takeScreenshotRequest() {
    auto r = std::move(m_screenshotPath);
    m_screenshotPath.reset();
    return r;
}

std::size_t Workbench::frameMemoryBudget() const {
    return m_settings.frameBudget() ? m_settings.frameBudget() : core::defaultFrameMemoryBudget();
}

void Workbench::setFrameMemoryBudget(std::size_t bytes) {
    m_settings.setFrameBudget(bytes);
    if (auto ds = dataset())
        ds->setCacheBudget(frameMemoryBudget());
}

} // namespace faultline::ui
