#include "core/session/session.hpp"

#include "core/session/command_label.hpp"

#include "core/io/input_error.hpp"
#include "core/surface/surface_cache.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <utility>

namespace faultline::core {

namespace fs = std::filesystem;

namespace {
constexpr std::size_t kSessionSurfaceBytes = std::size_t{512} << 20;
}

Session::Session() : m_surfaceCache(std::make_shared<SurfaceCache>(kSessionSurfaceBytes)) {
    detail::registerDataOps(m_ops);
    detail::registerSelectionOps(m_ops);
    detail::registerFaultOps(m_ops);
    detail::registerOutputOps(m_ops);
    detail::registerSurfaceOps(m_ops);
    detail::registerSessionOps(m_ops);
    detail::registerStrainOps(m_ops);
    // A group of commands that undoes as one (e.g. accepting every candidate).
    m_ops.add(
        "batch",
        [](Session& s, const Json& cmd) -> Json {
            args::onlyFields(cmd, {"commands"});
            const Json& list = args::require(cmd, "commands");
            if (!list.is_array())
                throw CommandError("batch: \"commands\" must be an array");
            std::vector<Json> inverses;
            try {
                for (const Json& c : list) {
                    bool changes = false;
                    Json inv = s.run(c, changes);
                    if (!changes)
                        throw CommandError("batch: only state-changing commands may be grouped");
                    inverses.push_back(std::move(inv));
                }
            } catch (...) {
                for (auto it = inverses.rbegin(); it != inverses.rend(); ++it) {
                    bool changes = false;
                    s.run(*it, changes);
                }
                throw;
            }
            std::reverse(inverses.begin(), inverses.end());
            return Json{{"op", "batch"}, {"commands", inverses}};
        },
        true);
}

Session::~Session() = default;

SurfaceCache& Session::surfaceCacheFor(std::size_t frameIndex) {
    // A live weak pointer to the same object: the same data (an expired one never matches, so
    // data opened at a freed dataset's address cannot inherit its surfaces).
    const auto held = m_surfaceData.lock();
    if (!held || held != m_dataset || frameIndex != m_surfaceFrameIndex) {
        m_surfaceCache->clear();
        m_surfaceData = m_dataset;
        m_surfaceFrameIndex = frameIndex;
    }
    return *m_surfaceCache;
}

namespace {
// A dock layout without what a click or a splitter drag changes (each area's active tab, the
// splits' ratios): which panels are where.
Json layoutShape(Json layout) {
    if (layout.is_object()) {
        layout.erase("active");
        layout.erase("ratio");
        for (auto& [key, value] : layout.items())
            value = layoutShape(value);
    } else if (layout.is_array()) {
        for (auto& value : layout)
            value = layoutShape(value);
    }
    return layout;
}
} // namespace

bool Session::knowsOp(const std::string& op) const {
    return op == "undo" || op == "redo" || m_ops.find(op) != nullptr;
}

std::vector<std::string> Session::knownOps() const {
    std::vector<std::string> out{"undo", "redo"};
    for (std::string& name : m_ops.names())
        out.push_back(std::move(name));
    return out;
}

void Session::registerOp(const std::string& op, OpHandler handler, bool changesState) {
    m_ops.add(op, std::move(handler), changesState);
}

Json Session::run(const Json& cmd, bool& changesState) {
    if (!cmd.is_object())
        throw CommandError("a command must be a JSON object, found " + cmd.dump());
    auto opIt = cmd.find("op");
    if (opIt == cmd.end() || !opIt->is_string())
        throw CommandError("a command needs an \"op\" string: " + cmd.dump());
    const std::string op = opIt->get<std::string>();
    const OpRegistry::Entry* entry = m_ops.find(op);
    if (!entry)
        throw CommandError("unknown op \"" + op + "\"");
    changesState = entry->changesState;
    m_markSavedAfterOp = false;
    Json inverse = entry->handler(*this, cmd);
    if (changesState) {
        syncDerived();
        ++m_version;
    }
    if (m_markSavedAfterOp)
        markSaved();
    m_markSavedAfterOp = false;
    return inverse;
}

Session::Preview Session::preview(std::span<const Json> commands) {
    static const std::set<std::string, std::less<>> kPreviewable = {
        "box.set", "threshold.add", "threshold.set", "threshold.remove", "camera.set"};
    // These ops change only boxes, thresholds and views' cameras: keep those and put them back.
    std::vector<CuttingBox> boxes = m_state.boxes;
    std::vector<VariableThreshold> thresholds = m_state.thresholds;
    std::vector<ViewState> views = m_state.views;
    Preview out;
    for (const Json& cmd : commands) {
        const std::string op = cmd.is_object() && cmd.contains("op") && cmd["op"].is_string()
                                   ? cmd["op"].get<std::string>()
                                   : std::string();
        const OpRegistry::Entry* entry = m_ops.find(op);
        if (!kPreviewable.count(op) || !entry)
            continue;
        const auto keepBoxes = m_state.boxes;
        const auto keepThresholds = m_state.thresholds;
        const auto keepViews = m_state.views;
        try {
            entry->handler(*this, cmd);
            ++out.applied;
        } catch (const CommandError&) {
            m_state.boxes = keepBoxes; // ops change nothing when they refuse; to be sure
            m_state.thresholds = keepThresholds;
            m_state.views = keepViews;
        }
    }
    out.boxes = std::exchange(m_state.boxes, std::move(boxes));
    out.thresholds = std::exchange(m_state.thresholds, std::move(thresholds));
    out.views = std::exchange(m_state.views, std::move(views));
    return out;
}

Json Session::execute(const Json& cmd) {
    bool changes = false;
    Json inverse = run(cmd, changes);
    if (!changes)
        throw CommandError("only state-changing ops can be part of another op");
    return inverse;
}

void Session::apply(const Json& cmd) {
    m_note.clear();
    m_moved.clear();
    const std::string op = cmd.is_object() && cmd.contains("op") && cmd["op"].is_string()
                               ? cmd["op"].get<std::string>()
                               : std::string();
    if (op == "undo" || op == "redo") {
        args::onlyFields(cmd, {});
        if (op == "undo" ? !undo() : !redo())
            throw CommandError(op + ": nothing to " + op);
    } else {
        // fault.add / fault.remove / fault.create: how many spheres they moved, for the label.
        const std::string name =
            op.rfind("fault.", 0) == 0 && cmd.contains("name") && cmd["name"].is_string()
                ? cmd["name"].get<std::string>()
                : std::string();
        auto faultSize = [&]() -> long long {
            const Fault* f = name.empty() ? nullptr : m_state.fault(name);
            return f ? static_cast<long long>(f->ids.size()) : 0;
        };
        const long long sizeBefore = faultSize();
        const bool wasModified = modified();
        const Json layoutBefore = op == "layout.set" ? m_state.dockLayout : Json();
        bool changesState = false;
        Json inverse = run(cmd, changesState);
        // Time, the camera, the panel shown in each area and the splitters' places are view
        // state (as in OVITO and ParaView): they leave nothing unsaved to ask about and make no
        // undo step (issue 41: the first Ctrl+Z after a rectangle undid a camera move; a click
        // on a tab became an undo step that emptied the redo history, so cancelling a save
        // prompt lost what redo would have brought back). A session still saves them. Moving a
        // panel to another area stays undoable: a tab dropped on the wrong edge goes back.
        const bool viewState =
            op == "frame.set" || op == "camera.set" ||
            (op == "layout.set" && layoutShape(layoutBefore) == layoutShape(m_state.dockLayout));
        if (viewState && !wasModified)
            markSaved();
        if (changesState && (op == "data.open" || op == "session.open")) {
            // Opening data or a session starts a new history, as in OVITO and ParaView: an undo
            // past it would leave an empty workbench bound to the file just opened, and a save
            // then writes that emptiness over it (issue 41).
            clearHistory();
        } else if (changesState && !viewState) {
            const bool sized = op == "fault.add" || op == "fault.remove" || op == "fault.create";
            std::string label =
                describeCommand(cmd, sized ? std::llabs(faultSize() - sizeBefore) : -1);
            // Spheres taken from other faults: the label says so ("add 285 spheres to "C1"
            // (moved 285 from Graben W)"), not a plain add (walkthrough of issue 41).
            if (sized && !m_moved.empty())
                label += " (moved " + m_moved + ")";
            m_undoLabels.push_back(std::move(label));
            m_undo.push_back(std::move(inverse));
            m_undoSerials.push_back(m_nextSerial++);
            m_redo.clear();
            m_redoSerials.clear();
            m_redoLabels.clear();
        }
    }
    m_journal.record(cmd);
}

void Session::checkAction(const Json& cmd) const {
    const std::string op = cmd.is_object() && cmd.contains("op") && cmd["op"].is_string()
                               ? cmd["op"].get<std::string>()
                               : std::string();
    const OpRegistry::Entry* entry = m_ops.find(op);
    if (!entry || entry->changesState)
        throw CommandError("settleAction: \"" + op + "\" is not an action");
}

std::uint64_t Session::reserveAction() { return m_journal.reserve(); }

void Session::settleAction(std::uint64_t place, const Json& cmd) {
    checkAction(cmd);
    m_journal.settle(place, cmd);
}

void Session::dropAction(std::uint64_t place) { m_journal.drop(place); }

void Session::dropPendingActions() { m_journal.dropPending(); }

std::size_t Session::pendingActions() const { return m_journal.pending(); }

void Session::clearHistory() {
    // A new history starts at a new position; an unmodified session stays unmodified.
    const bool wasSaved = historyPosition() == m_savedPosition;
    m_undoSerials.clear();
    m_redoSerials.clear();
    m_historyStart = m_nextSerial++;
    if (wasSaved && m_version == m_savedVersion)
        m_savedPosition = m_historyStart;
    m_undo.clear();
    m_redo.clear();
    m_undoLabels.clear();
    m_redoLabels.clear();
}

bool Session::undo() {
    if (m_undo.empty())
        return false;
    bool changes = false;
    Json redo = run(m_undo.back(), changes);
    m_undo.pop_back();
    m_redoSerials.push_back(m_undoSerials.back());
    m_undoSerials.pop_back();
    m_redo.push_back(std::move(redo));
    m_redoLabels.push_back(m_undoLabels.back());
    m_undoLabels.pop_back();
    return true;
}

bool Session::redo() {
    if (m_redo.empty())
        return false;
    bool changes = false;
    Json undo = run(m_redo.back(), changes);
    m_redo.pop_back();
    m_undoSerials.push_back(m_redoSerials.back());
    m_redoSerials.pop_back();
    m_undo.push_back(std::move(undo));
    m_undoLabels.push_back(m_redoLabels.back());
    m_redoLabels.pop_back();
    return true;
}

std::string Session::inputPath(const std::string& path) const {
    if (path.empty() || fs::path(path).is_absolute() || m_baseDir.empty())
        return path;
    return (fs::path(m_baseDir) / path).lexically_normal().string();
}

std::string Session::outputPath(const std::string& path) const {
    const std::string& dir = m_outputDir.empty() ? m_baseDir : m_outputDir;
    if (path.empty() || fs::path(path).is_absolute() || dir.empty())
        return path;
    return (fs::path(dir) / path).lexically_normal().string();
}

std::shared_ptr<Dataset> Session::openDataset(const std::vector<std::string>& paths) const {
    return m_datasetOpener ? m_datasetOpener(paths) : Dataset::open(paths);
}

void Session::syncDerived() {
    if (m_dataset)
        m_dataset->setStrains(m_state.strains);
}

void Session::setDataset(std::shared_ptr<Dataset> dataset) {
    m_dataset = std::move(dataset);
    syncDerived();
    m_visibilities.clear();
    ++m_version;
}

void Session::replaceState(SessionState state) {
    std::shared_ptr<Dataset> ds;
    if (!state.dataPaths.empty()) {
        ds = openDataset(state.dataPaths); // throws InputError naming the missing file
        if (state.frame >= ds->frameCount())
            throw InputError(state.dataPaths.front(),
                             "the session shows frame " + std::to_string(state.frame) +
                                 " but the data has " + std::to_string(ds->frameCount()) +
                                 " frames");
    }
    m_state = std::move(state);
    clearHistory();
    setDataset(std::move(ds));
}

std::shared_ptr<const Frame> Session::currentFrame() {
    if (!m_dataset)
        return nullptr;
    return m_dataset->frame(std::min(m_state.frame, m_dataset->frameCount() - 1));
}

std::size_t Session::frameOfView(const ViewState& view) const {
    const long long count = m_dataset ? static_cast<long long>(m_dataset->frameCount()) : 1;
    long long f = view.frame.relative ? static_cast<long long>(m_state.frame) + view.frame.value
                                      : view.frame.value;
    return static_cast<std::size_t>(std::clamp(f, 0LL, count - 1));
}

std::size_t Session::referenceFrameOfView(const ViewState& view) const {
    const long long count = m_dataset ? static_cast<long long>(m_dataset->frameCount()) : 1;
    return referenceFrame(view, frameOfView(view), static_cast<std::size_t>(count));
}

std::unique_ptr<std::vector<std::uint8_t>> Session::faultRowMask(const Frame& frame) const {
    return faultRowMask(m_state, frame);
}

std::unique_ptr<std::vector<std::uint8_t>> Session::faultRowMask(const SessionState& state,
                                                                 const Frame& frame) {
    const auto& filter = state.faultFilter;
    const bool anyHidden = std::any_of(state.faults.begin(), state.faults.end(),
                                       [](const Fault& f) { return !f.visible; });
    if (filter.mode == FaultFilter::Mode::All && !anyHidden)
        return nullptr;
    auto mask = std::make_unique<std::vector<std::uint8_t>>(
        frame.size(), filter.mode == FaultFilter::Mode::All ? 1 : 0);
    auto mark = [&](const Fault& f, std::uint8_t value) {
        for (std::int64_t id : f.ids)
            if (auto row = frame.rowOf(id))
                (*mask)[*row] = value;
    };
    switch (filter.mode) {
    case FaultFilter::Mode::All:
        for (const auto& f : state.faults)
            if (!f.visible)
                mark(f, 0);
        break;
    case FaultFilter::Mode::Labelled:
        for (const auto& f : state.faults)
            if (f.visible)
                mark(f, 1);
        break;
    case FaultFilter::Mode::Only:
        if (const Fault* f = state.fault(filter.fault))
            mark(*f, 1);
        break;
    }
    return mask;
}

namespace {

// Hash combining (boost's), over the fields visibility depends on.
void mix(std::uint64_t& h, std::uint64_t v) {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
}
void mix(std::uint64_t& h, double v) { mix(h, std::hash<double>{}(v)); }
void mix(std::uint64_t& h, const std::string& v) { mix(h, std::hash<std::string>{}(v)); }

} // namespace

std::uint64_t Session::faultFilterKey() {
    if (m_filterKeyVersion == m_version && m_filterKeyVersion != 0)
        return m_filterKey;
    // What faultRowMask reads: the filter, and each fault's visibility and members.
    std::uint64_t h = 0x51f1;
    mix(h, std::uint64_t(m_state.faultFilter.mode));
    mix(h, m_state.faultFilter.fault);
    for (const Fault& f : m_state.faults) {
        mix(h, f.name);
        mix(h, std::uint64_t(f.visible));
        mix(h, std::uint64_t(f.ids.size()));
        for (std::int64_t id : f.ids)
            mix(h, std::uint64_t(id));
    }
    m_filterKey = h;
    m_filterKeyVersion = m_version;
    return h;
}

Session::Visible Session::visibilityOf(const std::shared_ptr<const Frame>& frame,
                                       const std::vector<CuttingBox>& boxes,
                                       const std::vector<VariableThreshold>& thresholds) {
    if (!frame)
        return {std::make_shared<const VisibilityResult>(), 0};
    std::uint64_t key = faultFilterKey();
    mix(key, std::uint64_t(reinterpret_cast<std::uintptr_t>(frame.get())));
    for (const CuttingBox& b : boxes) {
        mix(key, std::uint64_t(b.enabled) | std::uint64_t(b.mode) << 1);
        for (int a = 0; a < 3; ++a)
            mix(key, b.min[a]), mix(key, b.max[a]);
    }
    mix(key, std::uint64_t(0xb0c5)); // boxes end
    for (const VariableThreshold& t : thresholds) {
        mix(key, t.variable);
        mix(key, t.low);
        mix(key, t.high);
        mix(key, std::uint64_t(t.enabled));
    }
    std::erase_if(m_visibilities, [](const VisibilityEntry& e) { return e.frame.expired(); });
    for (auto it = m_visibilities.begin(); it != m_visibilities.end(); ++it)
        if (it->key == key && it->frame.lock() == frame) {
            std::rotate(it, it + 1, m_visibilities.end()); // the most recently used last
            return {m_visibilities.back().result, key};
        }
    auto rowMask = faultRowMask(*frame);
    auto result = std::make_shared<const VisibilityResult>(
        computeVisibility(*frame, boxes, thresholds, rowMask.get()));
    // A few views, the session's own and a drag's preview at most are asked at once.
    constexpr std::size_t kKept = 8;
    if (m_visibilities.size() >= kKept)
        m_visibilities.erase(m_visibilities.begin());
    m_visibilities.push_back({frame, key, result});
    return {result, key};
}

const VisibilityResult& Session::visibility() {
    static const VisibilityResult kNone;
    auto frame = currentFrame();
    if (!frame)
        return kNone;
    // Held here until the next call, as the reference handed out promises.
    m_visibility = visibilityOf(frame, m_state.boxes, m_state.thresholds).result;
    return *m_visibility;
}

void Session::throwIfInterrupted(std::string_view op) const {
    if (m_interruptCheck && m_interruptCheck())
        throw CommandError(std::string(op) + ": interrupted");
}

} // namespace faultline::core
