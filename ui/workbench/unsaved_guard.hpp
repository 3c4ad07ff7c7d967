// The unsaved-work guard: a Save / Discard / Cancel question before anything would leave
// unsaved changes behind (quit, the window's close button, opening a session or other data,
// closing the data), and a Replace / Save as / Cancel question before a save writes over a file
// that is not the session's own or holds what the session does not (core::saveLossOverFile).
// One of the Workbench's parts with one job each (issue 39); what it needs of the workbench
// (saving, asking for a file name, saying things) comes through UnsavedGuard::Host.
#pragma once

#include "ui/widgets/item_registry.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

class UnsavedGuard {
  public:
    struct Host {
        virtual ~Host() = default;
        virtual bool hasUnsavedChanges() const = 0;
        virtual const std::string& sessionPath() const = 0;
        // Saves to `path`; `then` runs once it is written (the overwrite question may come
        // first).
        virtual void saveSessionAs(const std::string& path, std::function<void()> then) = 0;
        // Writes the session to `path` without asking.
        virtual void writeSession(const std::string& path, std::function<void()> then) = 0;
        // Opens the Save as dialog (purpose "save-session"); its answer comes back through
        // savedAsPicked or saveAsCancelled.
        virtual void askWhereToSave() = 0;
        virtual void info(std::string text) = 0;
        virtual ItemRegistry& items() = 0;
    };
    explicit UnsavedGuard(Host& host) : m_host(host) {}

    // Runs `proceed` at once when nothing is unsaved; else asks first. `target`: the file the
    // action opens, when it opens one; when that is the session's own file the question offers
    // "Save as..." instead of Save (saving there would write over the file being reopened).
    void guard(std::string action, std::function<void()> proceed, const std::string& target = {});
    // A save would write over `path`, losing `lost` (empty: only that the file exists).
    void askOverwrite(std::string path, std::vector<std::string> lost, std::function<void()> then);
    // The Save as dialog's answer.
    void savedAsPicked(const std::string& path);
    void saveAsCancelled() { m_afterSaveAs = {}; } // nothing proceeds

    bool unsavedOpen() const { return m_unsaved.has_value(); }
    bool unsavedOffersSave() const { return m_unsaved && !m_unsaved->reopening; }
    bool overwriteOpen() const { return m_overwrite.has_value(); }
    const std::vector<std::string>& overwriteLoss() const;

    // The questions, while they wait (between ImGui::NewFrame and ImGui::Render).
    void draw();

  private:
    void drawUnsaved();
    void drawOverwrite();
    Host& m_host;
    struct Unsaved {
        std::string action;
        std::function<void()> proceed;
        bool reopening = false; // the action opens the session's own file
    };
    std::optional<Unsaved> m_unsaved;
    struct Overwrite {
        std::string path;
        std::vector<std::string> lost;
        std::function<void()> then;
    };
    std::optional<Overwrite> m_overwrite;
    std::function<void()> m_afterSaveAs; // a question's Save, waiting for the Save as dialog
};

} // namespace faultline::ui
