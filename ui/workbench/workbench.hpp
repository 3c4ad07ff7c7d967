// Workbench: the whole GUI above the window: menus, the dock of panels, the status bar, and
// the link between them and the session. Panels never change the session: they emit commands
// (applied once the UI of a frame is built, so undo/redo and the journal cover everything) and,
// while a drag is under way, previews that the views show at once without a command.
#pragma once

#include "core/model/difference_column_cache.hpp"
#include "core/session/autosave.hpp"
#include "core/session/session.hpp"
#include "ui/context/panel_context.hpp"
#include "ui/dock/dock_layout.hpp"
#include "ui/dock/dock_space.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/viewport/session_figure.hpp"
#include "ui/viewport/view_renderer.hpp"
#include "ui/widgets/file_dialog.hpp"
#include "ui/widgets/item_registry.hpp"
#include "ui/workbench/background_exports.hpp"
#include "ui/workbench/data_opener.hpp"
#include "ui/workbench/help_windows.hpp"
#include "ui/workbench/key_commands.hpp"
#include "ui/workbench/movie_export.hpp"
#include "ui/workbench/recovery.hpp"
#include "ui/workbench/status_bar.hpp"
#include "ui/workbench/unsaved_guard.hpp"
#include "ui/workbench/user_settings.hpp"
#include "ui/workbench/view_composer.hpp"

#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace faultline::ui {

struct WorkbenchOptions {
    std::string stateDir;  // autosave and the journal of this run; empty: neither is written
    std::string configDir; // recent files; empty: not remembered
    double autosaveSeconds = 60.0;
};

// The Workbench composes the panels, the dock, the menus and the status bar; panels see it
// through PanelContext (ui/context/panel_context.hpp).
class Workbench final : public PanelContext, private UnsavedGuard::Host {
  public:
    explicit Workbench(core::Session& session, WorkbenchOptions options = {});
    ~Workbench();
    Workbench(const Workbench&) = delete;
    Workbench& operator=(const Workbench&) = delete;

    // Builds one frame of UI (between ImGui::NewFrame and ImGui::Render), applies the commands
    // it emitted and updates what the views show. `now` in seconds.
    void frame(double now);
    // Draws every view into its texture (after frame(), before ImGui::Render).
    void renderViews();

    // ---- PanelContext ----
    core::Session& session() { return m_session; }
    std::uint64_t sessionVersion() const override { return m_session.version(); }
    const core::SessionState& state() const override { return m_session.state(); }
    const std::shared_ptr<core::Dataset>& dataset() const override { return m_frames.dataset(); }
    using PanelContext::emit;
    void emit(core::Json command, std::function<void()> onApplied) override;
    void preview(const std::string& key, core::Json command) override;
    const std::vector<core::Json>& emittedThisFrame() const { return m_emittedLog; }

    const std::vector<ViewDisplay>& views() const override { return m_composer.views(); }
    const ViewDisplay* view(const std::string& name) const override;
    const ViewDisplay* mainDisplay() const override {
        return views().empty() ? nullptr : &views().front();
    }
    std::size_t displayFrame() const override;
    core::CameraState fitCamera(const core::ViewState& view, core::CameraState camera,
                                const std::array<double, 3>& lo,
                                const std::array<double, 3>& hi) const override;
    // fitCamera with what the view shows (its legend's title, range or names) when known.
    core::CameraState fitCameraBeside(const core::ViewState& view, const ViewDisplay* shown,
                                      core::CameraState camera, const std::array<double, 3>& lo,
                                      const std::array<double, 3>& hi) const;
    const std::vector<core::CuttingBox>& displayBoxes() const override {
        return m_composer.displayBoxes();
    }
    // Thresholds as shown (the session's with a drag's preview applied).
    const std::vector<core::VariableThreshold>& displayThresholds() const {
        return m_composer.displayThresholds();
    }
    FrameStore& frames() override { return m_frames; }
    ColumnCatalog& columns() override { return m_columns; }
    JobRunner& jobs() override { return m_jobs; }
    SurfaceStore& surfaces() override { return m_surfaces; }
    Playback& playback() override { return m_playback; }
    void play() override;
    void pause() override;
    void stepFrames(long long delta) override;
    void jumpToFrame(long long frame) override;
    UiSelection& selection() override { return m_selection; }
    const UiSelection& selection() const { return m_selection; }

    DockLayout& layout() override { return m_layout; }
    void commitLayout() override;

    ItemRegistry& items() override { return m_items; }
    double now() const override { return m_now; }
    float scale() const override { return m_scale; }
    void setScale(float s) { m_scale = s; }
    ViewRenderer* renderer() const override { return m_renderer; }
    void setRenderer(ViewRenderer* renderer) { m_renderer = renderer; }

    PanelExtensions& extensions() override { return m_extensions; }

    void info(std::string text) override; // PanelContext and UnsavedGuard::Host
    void error(std::string text) override;
    const std::string& lastMessage() const { return m_status.message(); }
    bool lastMessageIsError() const { return m_status.messageIsError(); }

    // ---- files ----
    // Opening data, sessions and the demo in the background (a session whose data moved asks
    // where it went: the "Where is the data?" prompt).
    DataOpener& opener() { return m_opener; }
    // CSV and surface exports on a worker thread, journalled where they were asked for.
    BackgroundExports& exports() { return m_exports; }
    // ---- movies (workbench_movie.cpp) ----
    // File > Export > Movie: the options (frames, step, size, rate, MP4 or PNG per frame).
    struct MovieOptions {
        int first = 0, last = 0, step = 1;
        int width = 1280, height = 720;
        int fps = 10;
        bool pngFrames = false; // a PNG per frame (path_%04d.png) instead of an MP4
    };
    MovieOptions movieOptions;
    void showMovieOptions(); // opens the options window on every frame of the data
    // The main view as a figure (issue 41: it was always the view's size on screen): its size
    // as on screen, a preset or typed, and an optional transparent background.
    struct FigureOptions {
        int size = 0; // 0 as on screen, 1 1920 x 1080, 2 3840 x 2160, 3 the width and height
        int width = 1920, height = 1080;
        bool transparent = false;
    };
    FigureOptions figureOptions;
    void showFigureOptions() { m_showFigureOptions = true; }
    // Renders the main view over the options' frames to `path` (the journal's render with
    // "frames"), one frame per UI frame (frames load ahead in the background); progress and
    // Cancel in a small window; journalled once written.
    void exportMovie(const std::string& path);
    bool movieRunning() const { return m_movie.running(); }
    std::pair<std::size_t, std::size_t> movieProgress() const { return m_movie.progress(); }
    void cancelMovie();
    void saveSession(); // to the session's file, else asks for one
    // `then` runs once the session is written.
    void saveSessionAs(const std::string& path, std::function<void()> then = {}) override;
    const std::string& sessionPath() const override { return m_sessionPath; }
    // Where export dialogs open: the last export's folder, else the session's, else the data's.
    std::string exportFolder() const override;
    const std::vector<std::string>& recentFiles() const { return m_settings.recent(); }
    // The memory frames may take (0: a quarter of RAM), remembered with the recent files.
    std::size_t frameMemoryBudget() const override;
    void setFrameMemoryBudget(std::size_t bytes) override;
    void requestScreenshot(const std::string& path) { m_screenshotPath = path; }
    // File > Export > Figure: the main view rendered offscreen (the journal's render op) at the
    // figure options' size (as on screen by default), so no dialog or panel is in it.
    void screenshotMainView(const std::string& path);
    std::pair<int, int> figureSize() const;     // in pixels, from the figure options
    std::pair<int, int> mainViewPixels() const; // the main view's size on screen
    std::optional<std::string> takeScreenshotRequest();
    bool hasScreenshotRequest() const { return m_screenshotPath.has_value(); }
    const std::string& journalPath() const { return m_journalPath; }
    FileDialog& fileDialog() override { return m_dialog; }
    bool quitRequested() const { return m_quit; }
    // Quit (menu, Ctrl+Q, the window's close button): asks Save / Discard / Cancel first when
    // the session has unsaved changes; quitRequested() turns true once the user chose.
    void requestQuit();
    // ---- unsaved work (workbench_unsaved.cpp) ----
    bool hasUnsavedChanges() const override { return m_session.modified(); }
    // Runs `proceed` at once when nothing is unsaved; else asks first ("<action>: save the
    // changes?" Save / Discard / Cancel): Save writes the session (asking where when it has no
    // file yet) and proceeds once it is written; Discard proceeds; Cancel forgets it.
    // `target`: the file the action opens, when it opens one. When that is the session's own
    // file the question offers "Save as..." instead of Save: saving there would write over the
    // very file being (re)opened.
    void guardUnsaved(std::string action, std::function<void()> proceed,
                      const std::string& target = {}) {
        m_unsaved.guard(std::move(action), std::move(proceed), target);
    }
    bool unsavedPromptOpen() const { return m_unsaved.unsavedOpen(); }
    bool unsavedPromptOffersSave() const { return m_unsaved.unsavedOffersSave(); }
    // Saving over an existing file that is not the session's own, or over the session's file
    // when it holds something the session to save does not (core::saveLoss): asks Replace /
    // Cancel first, naming what would be lost.
    bool overwritePromptOpen() const { return m_unsaved.overwriteOpen(); }
    const std::vector<std::string>& overwriteLoss() const { return m_unsaved.overwriteLoss(); }
    // "Faultline - name" with a "*" while there are unsaved changes.
    std::string windowTitle() const;
    void showHelp() { m_help.showKeys = true; }
    // Crash recovery: the session autosaved by a run that did not exit cleanly, offered once at
    // start (recover or discard); until decided, autosave keeps that file.
    const std::optional<core::PendingRecovery>& pendingRecovery() const {
        return m_recovery.pending();
    }
    void recover();
    void discardRecovery();

  private:
    // The keyboard commands (workbench_keys.cpp).
    static const std::vector<KeyCommand>& keyCommands();
    static const char* keysOf(const char* id);
    void runCommand(const char* id);
    void openDataDialog();
    void saveSessionAsDialog();
    void applyPending();
    void syncWithSession();
    void updatePlayback();
    void updateDisplay();
    void drawMenus();
    void drawDock(float top, float bottom);
    void drawPrompts();
    void drawMovie(); // the options window and the running export's progress
    void drawFigureOptions();
    void handleShortcuts();
    void handleDialog();

    core::Session& m_session;
    WorkbenchOptions m_options;
    FrameStore m_frames;
    ColumnCatalog m_columns;
    JobRunner m_jobs;
    SurfaceStore m_surfaces{m_jobs};
    // What the views show.
    ViewComposer m_composer{m_session, m_frames, m_surfaces, m_jobs};
    ItemRegistry m_items;
    DockLayout m_layout;
    bool m_layoutFollowsWindow = true; // the default layout, not arranged by the user yet
    float m_layoutWidth = 0;           // the window width a compact default was made for
    core::Json m_adoptedLayout;        // the session's layout as last adopted
    DockSpace m_dock;
    FileDialog m_dialog;
    std::vector<std::unique_ptr<Panel>> m_panels;
    ViewRenderer* m_renderer = nullptr;
    PanelExtensions m_extensions;
    UiSelection m_selection;
    float m_scale = 1.0f;
    double m_now = 0.0;

    std::vector<std::pair<core::Json, std::function<void()>>> m_pending;
    std::vector<core::Json> m_emittedLog;
    std::map<std::string, core::Json> m_previews;
    Playback m_playback;

    StatusBar m_status; // and the last message
    HelpWindows m_help;

    std::string m_sessionPath;
    std::string m_lastExportFolder;               // where the last export or screenshot went
    UserSettings m_settings{m_options.configDir}; // recent files, frame memory
    std::optional<std::string> m_screenshotPath;
    std::string m_journalPath;
    std::ofstream m_journal;
    Recovery m_recovery{m_options.stateDir}; // autosave, and a crashed run's session
    bool m_quit = false;
    bool m_showMovieOptions = false;
    bool m_showFigureOptions = false;
    UnsavedGuard m_unsaved{*this}; // Save / Discard / Cancel, Replace / Save as / Cancel
    void writeSession(const std::string& path, std::function<void()> then) override;
    void askWhereToSave() override; // the Save as dialog
    MovieExport m_movie{m_session}; // File > Export > Movie while it is written
    DataOpener m_opener{m_session, *this, m_settings, m_recovery,
                        [this](const std::string& path) { m_sessionPath = path; }};
    BackgroundExports m_exports{m_session, *this};
};

} // namespace faultline::ui
