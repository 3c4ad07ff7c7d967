#include "ui/workbench/workbench.hpp"

#include "ui/workbench/path_text.hpp"

#include "core/session/command_label.hpp"
#include "core/session/commands.hpp"

#include "core/io/input_error.hpp"
#include "core/selection/visibility.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

Workbench::Workbench(core::Session& session, WorkbenchOptions options)
    : m_session(session), m_options(std::move(options)) {
    m_layout = DockLayout::defaultLayout();
    m_panels = createPanels();
    addFaultMetricsSection(m_extensions);
    addFaultCandidatesSection(m_extensions);
    m_session.setDatasetOpener(
        [this](const std::vector<std::string>& paths) { return m_opener.dataset(paths); });
    m_frames.setDataset(m_session.dataset());
    if (!m_options.stateDir.empty()) {
        std::error_code ec;
        fs::create_directories(m_options.stateDir, ec);
        m_journalPath =
            (fs::path(m_options.stateDir) / ("journal-" + timestampForFile() + ".jsonl")).string();
        m_journal.open(m_journalPath, std::ios::app);
        if (m_journal) {
            m_journal << "// faultline workbench journal; run again with: faultline replay "
                      << m_journalPath << "\n";
            m_journal.flush();
            m_session.setJournalSink(
                [this](const Json& cmd) {
                    m_journal << cmd.dump() << "\n";
                    m_journal.flush();
                },
                [this](const Json& cmd) {
                    // Written again below once the exports asked for before it are; after a
                    // crash in between, uncomment it.
                    m_journal << "// held behind a running export: " << cmd.dump() << "\n";
                    m_journal.flush();
                });
        } else {
            m_journalPath.clear();
        }
    }
}

Workbench::~Workbench() {
    m_surfaces.clear(); // cancels surface builds
    m_extensions = {};  // their jobs are asked to stop (fault metrics) instead of awaited
    m_jobs.waitAll();
    m_recovery.exitCleanly(m_session); // nothing to offer next time
    m_session.dropPendingActions(); // exports not handed over: what waited behind them is written
    m_session.setJournalSink(nullptr);
    m_session.setDatasetOpener(nullptr);
}

void Workbench::emit(Json command, std::function<void()> onApplied) {
    m_emittedLog.push_back(command);
    m_pending.emplace_back(std::move(command), std::move(onApplied));
}

void Workbench::preview(const std::string& key, Json command) {
    m_previews[key] = std::move(command);
}

void Workbench::info(std::string text) { m_status.info(std::move(text), m_now); }

void Workbench::error(std::string text) { m_status.error(std::move(text), m_now); }

const ViewDisplay* Workbench::view(const std::string& name) const { return m_composer.view(name); }

std::size_t Workbench::displayFrame() const {
    for (const auto& [key, cmd] : m_previews)
        if (cmd.value("op", "") == "frame.set" && cmd.contains("frame") &&
            cmd["frame"].is_number_integer())
            return static_cast<std::size_t>(std::max<long long>(0, cmd["frame"].get<long long>()));
    if (m_playback.frame)
        return *m_playback.frame;
    return state().frame;
}

void Workbench::commitLayout() {
    Json doc = m_layout.toJson();
    if (doc != state().dockLayout)
        emit(core::cmd::layoutSet(doc));
}

void Workbench::frame(double now) {
    m_now = now;
    m_emittedLog.clear();
    m_previews.clear();
    m_selection.activeBoxFace = -1;
    m_jobs.poll();
    syncWithSession();
    updatePlayback();
    handleShortcuts();

    const ImGuiIO& io = ImGui::GetIO();
    drawMenus();
    const float menuHeight = ImGui::GetFrameHeight();
    const float statusHeight = std::round(ImGui::GetFrameHeight() + 8 * m_scale);
    drawDock(menuHeight, io.DisplaySize.y - statusHeight);
    m_status.draw(*this, statusHeight);
    handleDialog();
    m_help.draw(keyCommands(), m_scale, m_journalPath, m_renderer);
    drawPrompts();
    drawMovie();
    drawFigureOptions();
    m_unsaved.draw();

    applyPending();
    syncWithSession();
    updateDisplay();
    if (auto failed = m_recovery.autosave(m_session, m_now, m_options.autosaveSeconds))
        error(*failed);
    m_items.endFrame();
}

void Workbench::drawDock(float top, float bottom) {
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, top));
    ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, std::max(1.0f, bottom - top)));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0);
    ImGui::PushStyleColor(ImGuiCol_WindowBg,
                          IM_COL32(208, 213, 220, 255)); // the gaps between areas
    ImGui::Begin("##dockhost", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                     ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoNavFocus);
    ImGui::PopStyleColor();
    ImGui::PopStyleVar(3);
    DockSpace::Callbacks cb;
    cb.titleOf = [this](const std::string& id) -> const char* {
        for (auto& p : m_panels)
            if (id == p->id())
                return p->title();
        return "?";
    };
    cb.padded = [this](const std::string& id) {
        for (auto& p : m_panels)
            if (id == p->id())
                return p->padded();
        return true;
    };
    cb.drawPanel = [this](const std::string& id) {
        for (auto& p : m_panels)
            if (id == p->id())
                p->draw(*this);
    };
    // Until the user arranges the panels, the default layout follows the window's width.
    if (m_layoutFollowsWindow) {
        const float width = io.DisplaySize.x / std::max(m_scale, 0.1f);
        const bool compact = width < DockLayout::kCompactWidth;
        if (compact ? width != m_layoutWidth : m_layoutWidth != 0) {
            m_layout = DockLayout::defaultLayout(compact ? width : 0.0f);
            m_layoutWidth = compact ? width : 0.0f;
        }
    }
    const float gap = std::round(3 * m_scale);
    if (m_dock.draw(m_layout, ImVec2(gap, top + gap),
                    ImVec2(io.DisplaySize.x - 2 * gap, bottom - top - 2 * gap), m_scale, cb,
                    &m_items))
        commitLayout();
    ImGui::End();
}

void Workbench::applyPending() {
    auto pending = std::move(m_pending);
    m_pending.clear();
    for (const auto& [cmd, onApplied] : pending) {
        try {
            const std::string op = cmd.is_object() ? cmd.value("op", "") : std::string();
            // What undo / redo will revert or repeat, named before it happens.
            const std::string undoing = op == "undo"   ? m_session.undoLabel()
                                        : op == "redo" ? m_session.redoLabel()
                                                       : std::string();
            m_session.apply(cmd);
            if (onApplied)
                onApplied();
            if (op == "undo" && !undoing.empty())
                info("Undone: " + undoing);
            else if (op == "redo" && !undoing.empty())
                info("Redone: " + undoing);
            else if (op == "session.save")
                info("Saved the session to " + cmd.value("path", ""));
            else if (op == "export.csv")
                info("Exported " + cmd.value("path", ""));
            else if (!m_session.lastNote().empty()) {
                std::string note = m_session.lastNote();
                note[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(note[0])));
                info(note);
            }
        } catch (const core::CommandError& e) {
            error(core::describeFailure(cmd, e.what())); // words, not the op's name
        } catch (const core::InputError& e) {
            error(core::describeFailure(cmd, e.what()));
        } catch (const std::exception& e) {
            error(core::describeFailure(cmd, e.what()));
        }
    }
}

void Workbench::syncWithSession() {
    if (m_session.dataset() != m_frames.dataset()) {
        if (m_session.dataset())
            m_session.dataset()->setCacheBudget(frameMemoryBudget());
        m_frames.setDataset(m_session.dataset());
        m_composer.reset();
        m_surfaces.clear();
        Playback fresh;
        fresh.fps = m_playback.fps;
        fresh.loop = m_playback.loop;
        m_playback = fresh;
    }
    if (state().dockLayout != m_adoptedLayout) {
        m_adoptedLayout = state().dockLayout;
        const bool empty =
            m_adoptedLayout.is_null() || (m_adoptedLayout.is_object() && m_adoptedLayout.empty());
        std::string why;
        m_layoutFollowsWindow = empty;
        m_layoutWidth = 0;
        if (empty)
            m_layout = DockLayout::defaultLayout();
        else if (auto l = DockLayout::fromJson(m_adoptedLayout, panel_ids::all(), &why))
            m_layout = *l;
        else {
            m_layout = DockLayout::defaultLayout();
            error("The session's panel layout was not usable (" + why +
                  "); using the default layout");
        }
    }
    if (!m_selection.box.empty() && !state().box(m_selection.box))
        m_selection.box.clear();
    std::erase_if(m_selection.faults, [&](const std::string& f) { return !state().fault(f); });
    if (m_renderer)
        for (const auto& v : m_composer.views())
            if (!state().view(v.name))
                m_renderer->forget(v.name);
}

void Workbench::play() {
    auto ds = dataset();
    if (!ds || ds->frameCount() < 2)
        return;
    std::size_t f = displayFrame();
    if (f + 1 >= ds->frameCount() && m_playback.direction > 0)
        f = 0;
    m_playback.playing = true;
    m_playback.frame = f;
    m_playback.lastStep = m_now;
}

void Workbench::pause() {
    m_playback.playing = false;
    if (m_playback.frame && *m_playback.frame != state().frame)
        emit(core::cmd::frameSet(*m_playback.frame));
    m_playback.frame.reset();
}

void Workbench::stepFrames(long long delta) {
    auto ds = dataset();
    if (!ds)
        return;
    const long long n = static_cast<long long>(ds->frameCount());
    long long f = static_cast<long long>(displayFrame()) + delta;
    if (m_playback.loop)
        f = ((f % n) + n) % n;
    else
        f = std::clamp(f, 0LL, n - 1);
    if (m_playback.playing) {
        m_playback.frame = static_cast<std::size_t>(f);
        return;
    }
    m_playback.frame.reset();
    if (static_cast<std::size_t>(f) != state().frame)
        emit(core::cmd::frameSet(static_cast<std::size_t>(f)));
}

void Workbench::jumpToFrame(long long frame) {
    auto ds = dataset();
    if (!ds)
        return;
    const long long f = std::clamp(frame, 0LL, static_cast<long long>(ds->frameCount()) - 1);
    if (m_playback.playing) {
        m_playback.frame = static_cast<std::size_t>(f);
        return;
    }
    if (static_cast<std::size_t>(f) != state().frame)
        emit(core::cmd::frameSet(static_cast<std::size_t>(f)));
}

void Workbench::updatePlayback() {
    auto ds = dataset();
    m_frames.setLoop(m_playback.loop);
    if (!m_playback.playing || !ds || !m_playback.frame)
        return;
    const std::size_t n = ds->frameCount();
    const std::size_t cur = *m_playback.frame;
    // The prefetcher reads ahead in each view's direction of travel.
    if (m_now - m_playback.lastStep < 1.0 / std::max(m_playback.fps, 0.1))
        return;
    // The shown frame must have arrived before moving on: the old frame stays until then.
    const ViewDisplay* main = mainDisplay();
    if (main && main->loading())
        return;
    long long next = static_cast<long long>(cur) + m_playback.direction;
    if (next < 0 || next >= static_cast<long long>(n)) {
        if (!m_playback.loop) {
            pause();
            return;
        }
        next = m_playback.direction > 0 ? 0 : static_cast<long long>(n) - 1;
    }
    m_playback.frame = static_cast<std::size_t>(next);
    m_playback.lastStep = m_now;
}

void Workbench::updateDisplay() {
    m_composer.update({m_previews, displayFrame(), m_now, m_selection,
                       [this](const core::ViewState& v, const ViewDisplay& d, core::CameraState c) {
                           return fitCameraBeside(v, &d, c, d.framing.lo, d.framing.hi);
                       }});
}

core::CameraState Workbench::fitCamera(const core::ViewState& v, core::CameraState camera,
                                       const std::array<double, 3>& lo,
                                       const std::array<double, 3>& hi) const {
    return fitCameraBeside(v, m_composer.view(v.name), camera, lo, hi);
}

core::CameraState Workbench::fitCameraBeside(const core::ViewState& v, const ViewDisplay* d,
                                             core::CameraState camera,
                                             const std::array<double, 3>& lo,
                                             const std::array<double, 3>& hi) const {
    double w = 16, h = 9;
    if (auto r = m_items.find("view.image." + v.name); r && r->y1 > r->y0)
        w = r->x1 - r->x0, h = r->y1 - r->y0;
    // Leave the legend (drawn at the right edge) its own strip, measured as it will be drawn
    // (its title, tick labels or fault names), and centre the model in the rest (issue 41: a
    // long title's legend covered the block's east end).
    double legend = 0;
    if (!v.colorVariable.empty() && m_renderer && roomForLegend(int(w), int(h))) {
        const std::string title = d && !d->colorTitle.empty() ? d->colorTitle : v.colorVariable;
        const core::ValueRange range =
            d ? core::ValueRange{d->colorRange[0], d->colorRange[1]} : core::ValueRange{0, 1};
        const std::vector<LegendEntry> none;
        legend = legendStripPixels(title, range, false, d ? d->legend : none, int(w), int(h));
        legend = std::min(0.45 * w, legend);
    }
    fitBesideLegend(camera, lo, hi, w, h, legend);
    return camera;
}

void Workbench::renderViews() {
    if (!m_renderer)
        return;
    // Filled by the viewports panel: the pixel size each view was given this frame.
    for (const ViewDisplay& d : m_composer.views()) {
        const core::ViewState* v = state().view(d.name);
        auto size = m_items.find("view.image." + d.name);
        if (!v || !size)
            continue;
        ViewScene scene;
        scene.view = d.name;
        scene.frame = d.frame;
        scene.visible = d.visibility ? &d.visibility->mask : nullptr;
        scene.visibleKey = d.visibilityKey;
        scene.colorVariable = d.colorTitle;
        scene.valueLegend = !d.colorHasNoValue;
        scene.colorColumn = d.colorColumn;
        scene.colorMap = v->colorMap;
        scene.surfaces = d.surfaces;
        scene.palette = d.palette;
        scene.legend = d.legend;
        scene.contextPoints = v->contextPoints;
        scene.colorRange = d.colorRange;
        scene.camera = d.camera;
        for (const auto& b : m_composer.displayBoxes())
            if (b.enabled || b.name == m_selection.box) {
                if (b.name == m_selection.box && m_selection.editBoxInView) {
                    scene.selectedBox = scene.boxes.size();
                    if (m_selection.activeBoxFace >= 0)
                        scene.activeFace = m_selection.activeBoxFace;
                }
                scene.boxes.push_back(b);
            }
        const float fb = ImGui::GetIO().DisplayFramebufferScale.x;
        scene.width = static_cast<int>((size->x1 - size->x0) * fb);
        scene.height = static_cast<int>((size->y1 - size->y0) * fb);
        if (scene.width > 0 && scene.height > 0)
            m_renderer->render(scene);
    }
}

} // namespace faultline::ui
