#include "ui/workbench/data_opener.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/data/dataset.hpp"
#include "core/session/commands.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "core/synth/demo_model.hpp"
#include "ui/context/panel_context.hpp"
#include "ui/workbench/recovery.hpp"
#include "ui/workbench/user_settings.hpp"

#include <algorithm>
#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

namespace {

bool isSessionFile(const std::string& path) {
    const std::string suffix = ".faultline.json";
    return path.size() >= suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string shortName(const std::vector<std::string>& paths) {
    if (paths.empty())
        return "data";
    std::string n = fs::path(paths.front()).filename().string();
    if (paths.size() > 1)
        n += " and " + std::to_string(paths.size() - 1) + " more";
    return n;
}

} // namespace

void DataOpener::openPath(const std::string& path) {
    if (isSessionFile(path))
        openSession(path);
    else
        openData({path});
}

void DataOpener::openData(std::vector<std::string> paths, std::function<void()> then) {
    for (auto& p : paths)
        p = absolutePath(p);
    const std::string name = shortName(paths);
    // The work runs on its own thread; the closure it returns runs on the UI thread.
    m_ctx.jobs().start(
        "Opening " + name,
        [this, paths, then](JobControl& control) -> std::function<void()> {
            // Indexing every file is the first 60 %, reading the frame shown the rest.
            auto ds = core::Dataset::open(paths, [&control](double f) {
                control.setProgress(static_cast<float>(0.6 * f));
                return !control.cancelled();
            });
            ds->frame(0); // the frame data.open shows
            control.setProgress(1.0f);
            return [this, paths, ds, then] {
                remember(paths, ds);
                const bool pristine = !m_session.modified();
                m_ctx.emit(core::cmd::dataOpen(paths), [this, paths, then, pristine] {
                    if (pristine) // data opened into an untouched session: nothing to save yet
                        m_session.markSaved();
                    m_settings.addRecent(paths.size() == 1 ? paths.front() : std::string());
                    if (then)
                        then();
                });
            };
        },
        [this, name](const std::string& why) { m_ctx.error("Cannot open " + name + ": " + why); },
        m_ctx.now());
}

void DataOpener::openSession(const std::string& pathIn, std::vector<std::string> data) {
    const std::string path = absolutePath(pathIn);
    const std::string name = fs::path(path).filename().string();
    m_ctx.jobs().start(
        "Opening " + name,
        [this, path, data](JobControl& control) -> std::function<void()> {
            core::SessionState s = core::loadSessionFile(path); // validated
            if (!data.empty())
                s.dataPaths = data;
            // Data that moved: ask where it went instead of failing.
            for (const auto& p : s.dataPaths)
                if (p.find_first_of("*?[%") == std::string::npos && !fs::exists(p))
                    return [this, path, paths = s.dataPaths] {
                        m_missingData = MissingData{path, paths};
                    };
            std::shared_ptr<core::Dataset> ds;
            if (!s.dataPaths.empty()) {
                ds = core::Dataset::open(s.dataPaths, [&control](double f) {
                    control.setProgress(static_cast<float>(0.6 * f));
                    return !control.cancelled();
                });
                if (s.frame < ds->frameCount())
                    ds->frame(s.frame);
            }
            control.setProgress(1.0f);
            return [this, path, s, ds, data] {
                if (ds)
                    remember(s.dataPaths, ds);
                const Json cmd = core::cmd::sessionOpen(path, data);
                const bool recovering = m_recovery.recovering();
                m_ctx.emit(cmd, [this, path, recovering] {
                    if (recovering) { // saving asks for a real place, not the recovery file
                        m_recovery.opened();
                        m_ctx.info("Recovered the autosaved session: File > Save as to keep it");
                        return;
                    }
                    m_settings.addRecent(path);
                    if (m_sessionFileOpened)
                        m_sessionFileOpened(path);
                });
            };
        },
        [this, name](const std::string& why) {
            m_recovery.abandoned();
            m_ctx.error("Cannot open " + name + ": " + why);
        },
        m_ctx.now());
}

void DataOpener::relocate(const std::string& pickedFile) {
    if (!m_missingData)
        return;
    // One file: that file. Several (a series): the same names in the picked file's folder.
    MissingData missing = std::move(*m_missingData);
    m_missingData.reset();
    std::vector<std::string> paths;
    if (missing.paths.size() == 1) {
        paths.push_back(absolutePath(pickedFile));
    } else {
        const fs::path folder = fs::path(absolutePath(pickedFile)).parent_path();
        for (const auto& p : missing.paths)
            paths.push_back((folder / fs::path(p).filename()).string());
    }
    openSession(missing.session, paths);
}

void DataOpener::forgetMissing() {
    m_missingData.reset();
    m_recovery.abandoned(); // a recovered session left closed: autosave goes on
}

void DataOpener::openDemo() {
    // The demo opens where its faults are: the last frame, coloured by broken bonds, with only
    // the spheres of three or more broken bonds shown (the fault zones inside the opaque block)
    // and the rest as faint points for context, seen obliquely. One batch: one undo gives the
    // whole block back.
    auto showFaults = [this] {
        if (!m_session.dataset())
            return;
        const core::SessionState& state = m_session.state();
        std::vector<Json> batch;
        batch.push_back(core::cmd::frameSet(m_session.dataset()->frameCount() - 1));
        if (state.view("main") && state.view("main")->colorVariable.empty())
            batch.push_back(core::cmd::ColorSet("main").variable("broken_bonds").map("blue-red"));
        if (!state.threshold("broken_bonds"))
            batch.push_back(core::cmd::ThresholdAdd("broken_bonds").low(3).high(1e30));
        if (state.view("main")) {
            batch.push_back(core::cmd::ViewSet("main").contextPoints(true));
            // From above the south-west corner, so the faults' dip and their run show.
            batch.push_back(core::cmd::CameraSet("main").azimuth(-30).elevation(35));
        }
        // The demo's view is where a session starts, not the user's work.
        const bool pristine = !m_session.modified();
        m_ctx.emit(core::cmd::batch(std::move(batch)), [this, pristine] {
            // "Undone: the demo's starting view", not "Undone: 5 changes" (walkthrough).
            m_session.relabelLastUndo("the demo's starting view (its last frame, broken_bonds "
                                      ">= 3)");
            if (pristine)
                m_session.markSaved();
        });
    };
    if (auto path = core::existingDemoModel()) {
        openData({*path}, showFaults);
        return;
    }
    m_ctx.jobs().start(
        "Making the demo model (once)",
        [this, showFaults](JobControl& control) -> std::function<void()> {
            const std::string path = core::ensureDemoModel([&control](double fraction) {
                control.setProgress(static_cast<float>(fraction));
                return !control.cancelled();
            });
            return [this, path, showFaults] { openData({path}, showFaults); };
        },
        [this](const std::string& why) { m_ctx.error("Cannot make the demo model: " + why); },
        m_ctx.now());
}

std::shared_ptr<core::Dataset> DataOpener::dataset(const std::vector<std::string>& paths) {
    for (auto it = m_datasets.begin(); it != m_datasets.end(); ++it)
        if (it->first == paths) {
            auto ds = it->second;
            std::rotate(m_datasets.begin(), it, it + 1); // most recent first
            return ds;
        }
    auto ds = core::Dataset::open(paths); // not prepared in the background: e.g. a replayed undo
    remember(paths, ds);
    return ds;
}

void DataOpener::remember(const std::vector<std::string>& paths,
                          std::shared_ptr<core::Dataset> ds) {
    std::erase_if(m_datasets, [&](const auto& e) { return e.first == paths; });
    m_datasets.insert(m_datasets.begin(), {paths, std::move(ds)});
    if (m_datasets.size() > 3)
        m_datasets.pop_back();
}

} // namespace faultline::ui
