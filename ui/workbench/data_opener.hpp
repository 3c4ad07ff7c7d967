// Opening data and sessions: the files are indexed and the frame shown read on a worker thread
// (progress and Cancel in the status bar), then data.open / session.open is emitted so undo and
// the journal cover it. Also the demo model (made once), a session whose data moved (asks
// where it went), and the few datasets opened last, so undoing past an open or reopening does
// not read the files again.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace faultline::core {
class Dataset;
class Session;
} // namespace faultline::core

namespace faultline::ui {

class PanelContext;
class Recovery;
class UserSettings;

class DataOpener {
  public:
    // `ctx`: the jobs, emit, the clock and the messages. `sessionFileOpened(path)` runs when a
    // session file (not a recovered one) was opened: it is now the session's file.
    DataOpener(core::Session& session, PanelContext& ctx, UserSettings& settings,
               Recovery& recovery, std::function<void(const std::string&)> sessionFileOpened)
        : m_session(session), m_ctx(ctx), m_settings(settings), m_recovery(recovery),
          m_sessionFileOpened(std::move(sessionFileOpened)) {}

    void openPath(const std::string& path); // data or *.faultline.json
    // `then` runs once the data is open (after its data.open was applied).
    void openData(std::vector<std::string> paths, std::function<void()> then = {});
    // `data`: where the session's data is now, when it moved (else the paths it names). When
    // its data is missing, missingData() says so until relocate() or forgetMissing().
    void openSession(const std::string& path, std::vector<std::string> data = {});
    // The generator's demo model: made once in the per-user data folder (a background job),
    // then opened at its last frame with the faults shown.
    void openDemo();

    // A session whose data moved: which session and the paths it named.
    struct MissingData {
        std::string session;
        std::vector<std::string> paths;
    };
    const std::optional<MissingData>& missingData() const { return m_missingData; }
    void relocate(const std::string& pickedFile); // the picked file stands for the data
    void forgetMissing();                         // the session stays closed

    // The dataset of `paths`: one of the last three opened, else opened now (the session's
    // opener, e.g. for a replayed undo of a data.open).
    std::shared_ptr<core::Dataset> dataset(const std::vector<std::string>& paths);

  private:
    void remember(const std::vector<std::string>& paths, std::shared_ptr<core::Dataset> ds);

    core::Session& m_session;
    PanelContext& m_ctx;
    UserSettings& m_settings;
    Recovery& m_recovery;
    std::function<void(const std::string&)> m_sessionFileOpened;
    std::optional<MissingData> m_missingData;
    std::vector<std::pair<std::vector<std::string>, std::shared_ptr<core::Dataset>>> m_datasets;
};

} // namespace faultline::ui
