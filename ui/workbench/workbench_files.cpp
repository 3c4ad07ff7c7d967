// The workbench's files: opening data and sessions in the background, saving, recent files,
// autosave next to the journal, screenshot requests.
#include "ui/workbench/workbench.hpp"

#include "core/io/input_error.hpp"
#include "core/session/atomic_file.hpp"
#include "core/session/commands.hpp"
#include "core/session/csv_exports.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/save_loss.hpp"
#include "core/session/session_json.hpp"
#include "core/synth/demo_model.hpp"
#include "ui/context/job_interrupter.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

namespace {

// A background export's place in the journal (Session::reserveAction): given up when the job
// ends without settling it (failed or cancelled). Held only by closures that live and die on
// the UI thread.
struct JournalPlace {
    explicit JournalPlace(core::Session& s) : session(s), place(s.reserveAction()) {}
    ~JournalPlace() { session.dropAction(place); }
    JournalPlace(const JournalPlace&) = delete;
    JournalPlace& operator=(const JournalPlace&) = delete;
    core::Session& session;
    std::uint64_t place;
};

bool isSessionFile(const std::string& path) {
    const std::string suffix = ".faultline.json";
    return path.size() >= suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string absolute(const std::string& path) {
    std::error_code ec;
    auto p = fs::absolute(path, ec);
    return ec ? path : p.lexically_normal().string();
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

void Workbench::openPath(const std::string& path) {
    if (isSessionFile(path))
        openSession(path);
    else
        openData({path});
}

void Workbench::openData(std::vector<std::string> paths, std::function<void()> then) {
    for (auto& p : paths)
        p = absolute(p);
    const std::string name = shortName(paths);
    // The work runs on its own thread; the closure it returns runs on the UI thread.
    m_jobs.start(
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
                rememberDataset(paths, ds);
                const bool pristine = !m_session.modified();
                emit(core::cmd::dataOpen(paths), [this, paths, then, pristine] {
                    if (pristine) // data opened into an untouched session: nothing to save yet
                        m_session.markSaved();
                    m_settings.addRecent(paths.size() == 1 ? paths.front() : std::string());
                    if (then)
                        then();
                });
            };
        },
        [this, name](const std::string& why) { error("Cannot open " + name + ": " + why); }, m_now);
}

void Workbench::openSession(const std::string& pathIn, std::vector<std::string> data) {
    const std::string path = absolute(pathIn);
    const std::string name = fs::path(path).filename().string();
    m_jobs.start(
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
                    rememberDataset(s.dataPaths, ds);
                const Json cmd = core::cmd::sessionOpen(path, data);
                const bool recovering = m_recovery.recovering();
                emit(cmd, [this, path, recovering] {
                    if (recovering) { // saving asks for a real place, not the recovery file
                        m_recovery.opened();
                        info("Recovered the autosaved session: File > Save as to keep it");
                        return;
                    }
                    m_sessionPath = path;
                    m_settings.addRecent(path);
                });
            };
        },
        [this, name](const std::string& why) {
            m_recovery.abandoned();
            error("Cannot open " + name + ": " + why);
        },
        m_now);
}

void Workbench::recover() {
    if (const auto path = m_recovery.recover())
        openSession(*path);
}

void Workbench::discardRecovery() { m_recovery.discard(); }

void Workbench::relocateData(const std::string& pickedFile) {
    if (!m_missingData)
        return;
    // One file: that file. Several (a series): the same names in the picked file's folder.
    MissingData missing = std::move(*m_missingData);
    m_missingData.reset();
    std::vector<std::string> paths;
    if (missing.paths.size() == 1) {
        paths.push_back(absolute(pickedFile));
    } else {
        const fs::path folder = fs::path(absolute(pickedFile)).parent_path();
        for (const auto& p : missing.paths)
            paths.push_back((folder / fs::path(p).filename()).string());
    }
    openSession(missing.session, paths);
}

void Workbench::openDemo() {
    // The demo opens where its faults are: the last frame, coloured by broken bonds, with only
    // the spheres of three or more broken bonds shown (the fault zones inside the opaque block)
    // and the rest as faint points for context, seen obliquely. One batch: one undo gives the
    // whole block back.
    auto showFaults = [this] {
        if (!m_session.dataset())
            return;
        std::vector<Json> batch;
        batch.push_back(core::cmd::frameSet(m_session.dataset()->frameCount() - 1));
        if (state().view("main") && state().view("main")->colorVariable.empty())
            batch.push_back(core::cmd::ColorSet("main").variable("broken_bonds").map("blue-red"));
        if (!state().threshold("broken_bonds"))
            batch.push_back(core::cmd::ThresholdAdd("broken_bonds").low(3).high(1e30));
        if (state().view("main")) {
            batch.push_back(core::cmd::ViewSet("main").contextPoints(true));
            // From above the south-west corner, so the faults' dip and their run show.
            batch.push_back(core::cmd::CameraSet("main").azimuth(-30).elevation(35));
        }
        // The demo's view is where a session starts, not the user's work.
        const bool pristine = !m_session.modified();
        emit(core::cmd::batch(std::move(batch)), [this, pristine] {
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
    m_jobs.start(
        "Making the demo model (once)",
        [this, showFaults](JobControl& control) -> std::function<void()> {
            const std::string path = core::ensureDemoModel([&control](double fraction) {
                control.setProgress(static_cast<float>(fraction));
                return !control.cancelled();
            });
            return [this, path, showFaults] { openData({path}, showFaults); };
        },
        [this](const std::string& why) { error("Cannot make the demo model: " + why); }, m_now);
}

void Workbench::exportSurfaces(std::vector<std::string> faults, const std::string& pathIn, bool vdb,
                               bool glyphs) {
    const std::string path = absolute(pathIn);
    std::shared_ptr<const core::Frame> frame;
    try {
        frame = m_session.currentFrame();
    } catch (const std::exception& e) {
        return error(std::string("Cannot export: ") + e.what());
    }
    if (!frame || faults.empty())
        return error("Cannot export: no data or no fault");
    std::vector<core::FaultSurfaceRequest> requests;
    // The visible spheres of the current frame as the export.vdb / export.gltf ops take them
    // (not a view's: it may show a drag's preview), so a replay exports the same.
    const auto visibility = std::make_shared<const core::VisibilityResult>(m_session.visibility());
    for (const auto& name : faults) {
        const core::Fault* f = m_surfaces.sourceOf(state(), name, frame, visibility);
        if (!f)
            return error("Cannot export: no fault named " + name);
        core::SurfaceSettings st;
        st.fault = name;
        if (const core::SurfaceSettings* saved = state().surface(name))
            st = *saved;
        requests.push_back({*f, st});
    }
    const Json cmd = vdb ? core::cmd::exportVdb(faults.front(), path)
                         : core::cmd::exportGltf(faults, path, glyphs);
    auto place = std::make_shared<JournalPlace>(m_session);
    m_jobs.start(
        "Exporting " + fs::path(path).filename().string(),
        [this, frame, requests, path, vdb, cmd, cache = m_surfaces.cache(),
         frameIndex = state().frame, glyphs,
         at = place->place](JobControl& control) -> std::function<void()> {
            // Surfaces shown in the views come from their cache, not built again.
            JobInterrupter interrupter(control);
            const core::SurfaceReuse reuse{cache.get(), frameIndex};
            if (vdb)
                core::writeFaultVdb(*frame, requests.front(), path, &interrupter, reuse);
            else
                core::writeFaultsGlb(*frame, requests, path, glyphs, &interrupter, reuse);
            return [this, cmd, path, at] {
                m_session.settleAction(at, cmd); // replayed like any export, where it was asked for
                info("Exported " + path);
            };
        },
        [this, place](const std::string& why) { error("Export failed: " + why); }, m_now);
}

void Workbench::exportCsv(core::Json cmd) {
    const std::string path = absolute(cmd.value("path", std::string()));
    cmd["path"] = path;
    auto place = std::make_shared<JournalPlace>(m_session);
    m_jobs.start(
        "Exporting " + fs::path(path).filename().string(),
        [this, snapshot = state(), data = m_session.dataset(), cmd, path,
         at = place->place](JobControl& control) -> std::function<void()> {
            // Cancel in the status bar stops it between frames; no file is written.
            core::writeFileAtomically(path,
                                      core::exportCsvText(snapshot, data, cmd, {}, [&control] {
                                          if (control.cancelled())
                                              throw std::runtime_error("cancelled");
                                      }));
            return [this, cmd, path, at] {
                m_session.settleAction(at, cmd); // replayed like any export, where it was asked for
                info("Exported " + path);
            };
        },
        [this, place](const std::string& why) { error("Export failed: " + why); }, m_now);
}

void Workbench::rememberDataset(const std::vector<std::string>& paths,
                                std::shared_ptr<core::Dataset> ds) {
    std::erase_if(m_datasets, [&](const auto& e) { return e.first == paths; });
    m_datasets.insert(m_datasets.begin(), {paths, std::move(ds)});
    if (m_datasets.size() > 3)
        m_datasets.pop_back();
}

void Workbench::askWhereToSave() { saveSessionAsDialog(); }

void Workbench::saveSession() {
    if (m_sessionPath.empty()) {
        askWhereToSave();
        return;
    }
    saveSessionAs(m_sessionPath);
}

void Workbench::saveSessionAs(const std::string& pathIn, std::function<void()> then) {
    const std::string path = absolute(pathIn);
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
