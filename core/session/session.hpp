// Session: the session state, the commands that change it (each returns its inverse, giving
// unlimited undo/redo), the journal of everything applied, the open dataset and the derived
// data of the current frame (visibility). The UI, the CLI and replay all drive it the same way.
#pragma once

#include "core/data/dataset.hpp"
#include "core/faults/frame_loader.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/command_args.hpp"
#include "core/session/journal_recorder.hpp"
#include "core/session/op_registry.hpp"
#include "core/session/session_state.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace faultline::core {

class SurfaceCache;

class Session {
  public:
    // A state op returns the command that undoes it; an action (export, render, save) returns
    // null and is not undoable. Either throws CommandError, having changed nothing.
    using OpHandler = OpRegistry::Handler;

    Session();
    ~Session();

    const SessionState& state() const { return m_state; }
    std::uint64_t version() const { return m_version; } // grows with every change
    // Changed since the state was last saved (session.save) or opened (session.open); a new
    // session is unmodified. markSaved() makes the current state the saved one.
    // Undoing back to the saved state, or redoing back to it, leaves it unmodified (issue 42:
    // four undos and four redos after a save asked to save again).
    bool modified() const {
        return m_version != m_savedVersion && historyPosition() != m_savedPosition;
    }
    void markSaved() {
        m_savedVersion = m_version;
        m_savedPosition = historyPosition();
    }
    // For session.open's handler: the state it installs counts as saved once the op completes.
    void markSavedAfterThisOp() { m_markSavedAfterOp = true; }
    // Long ops (exports over every frame) ask between frames whether to stop: a check that
    // returns true stops them with CommandError("<op>: interrupted") (the Python module's
    // Ctrl+C). None by default.
    void setInterruptCheck(std::function<bool()> check) { m_interruptCheck = std::move(check); }
    void throwIfInterrupted(std::string_view op) const;

    // Runs one command (including {"op":"undo"} and {"op":"redo"}) and records it in the journal.
    void apply(const Json& cmd);
    // An action (an op that changes no state, such as an export) that the caller carries out
    // itself in the background keeps its place in the journal from the moment it is asked for:
    // lines recorded after it wait until it is settled, so a replay runs it on the state it read,
    // not on what the user changed while it ran.
    std::uint64_t reserveAction();
    // It worked: records `cmd` in the reserved place. Throws CommandError for an unknown op or
    // one that changes state.
    void settleAction(std::uint64_t place, const Json& cmd);
    // It failed or was cancelled: the place records nothing.
    void dropAction(std::uint64_t place);
    // Gives up every place still open (shutdown), so the lines waiting behind them are written.
    void dropPendingActions();
    std::size_t pendingActions() const;
    bool canUndo() const { return !m_undo.empty(); }
    bool canRedo() const { return !m_redo.empty(); }
    bool undo(); // false when there is nothing to undo
    bool redo();
    std::size_t undoDepth() const { return m_undo.size(); }
    // Forgets every undo and redo step. data.open and session.open do this themselves: opening
    // starts a new history (nothing undoes an open, so nothing can empty what was opened).
    void clearHistory();
    // What undo and redo would revert or repeat, in words ("add 279 spheres to F1"); empty when
    // there is nothing to undo or redo. Time (frame.set) is view state, as in OVITO and
    // ParaView: moving through frames makes no undo step (and keeps what redo would repeat), and
    // does not make an unmodified session modified.
    std::string undoLabel() const {
        return m_undoLabels.empty() ? std::string() : m_undoLabels.back();
    }
    // Names the last undo step in words its command cannot give (the demo's starting view).
    void relabelLastUndo(std::string label) {
        if (!m_undoLabels.empty())
            m_undoLabels.back() = std::move(label);
    }
    std::string redoLabel() const {
        return m_redoLabels.empty() ? std::string() : m_redoLabels.back();
    }

    // What a live edit (a drag of a box face, a histogram threshold, the camera) would show,
    // without applying it: `commands` run in order through the same ops as apply() on the
    // session's selection and views, which are then put back as they were; no journal, no
    // undo, no version change. Only box.set, threshold.add/set/remove and camera.set preview;
    // a command its op refuses (or another op) is skipped, so an invalid edit shows nothing.
    struct Preview {
        std::vector<CuttingBox> boxes;
        std::vector<VariableThreshold> thresholds;
        std::vector<ViewState> views;
        std::size_t applied = 0; // commands that previewed
    };
    Preview preview(std::span<const Json> commands);

    // What the last applied command did beyond its label, for the status line ("moved 37
    // spheres from C2 to F1"); empty when nothing. Ops add to it while they run.
    const std::string& lastNote() const { return m_note; }
    void addNote(const std::string& note) { m_note += (m_note.empty() ? "" : "; ") + note; }
    // Spheres the last command took from other faults ("2 from C2, 1 from F3") into `into`:
    // said in the note and in its undo step's label.
    void noteMoved(const std::string& moved, const std::string& into) {
        m_moved = moved;
        addNote("moved " + moved + " to " + into);
    }

    // Ops known to this session: the built-in ones and any registered by outer layers.
    bool knowsOp(const std::string& op) const;
    std::vector<std::string> knownOps() const;
    // Lets a layer above core add an op (the UI library adds "render").
    void registerOp(const std::string& op, OpHandler handler, bool changesState = false);

    // Every command applied, in order, as given (the journal). `sink`, when set, receives each
    // line as it is applied (the GUI appends it to the session's journal file).
    const std::vector<Json>& journal() const { return m_journal.lines(); }
    // `held`, when set, also receives each line the moment it is recorded behind an unsettled
    // background action (reserveAction), before `sink` gets it in its place: the GUI writes it as
    // a comment, so a crash during a long export loses none of the user's commands.
    void setJournalSink(std::function<void(const Json&)> sink,
                        std::function<void(const Json&)> held = nullptr) {
        m_journal.setSinks(std::move(sink), std::move(held));
    }

    // Paths in commands are relative to baseDir (the journal's folder); outputs (exports,
    // renders, saves) go under outputDir when set, else baseDir.
    void setBaseDir(std::string dir) { m_baseDir = std::move(dir); }
    void setOutputDir(std::string dir) { m_outputDir = std::move(dir); }
    const std::string& baseDir() const { return m_baseDir; }
    std::string inputPath(const std::string& path) const;
    std::string outputPath(const std::string& path) const;
    // Replay on other data: data.open uses these paths instead of the journal's.
    void setDataOverride(std::vector<std::string> paths) { m_dataOverride = std::move(paths); }
    // replay --frames / --shard: the frames per-frame work (CSV exports over time, renders of
    // a frame range) covers. Default: every frame.
    void setFrameSelection(const FrameSelection& selection) { m_frameSelection = selection; }
    const FrameSelection& frameSelection() const { return m_frameSelection; }

    // How data.open, session.open and replaceState turn paths into a dataset. The default is
    // Dataset::open; the GUI installs one that hands over a dataset it opened in the background,
    // so applying the command does not block. The opener throws InputError like Dataset::open.
    using DatasetOpener = std::function<std::shared_ptr<Dataset>(const std::vector<std::string>&)>;
    void setDatasetOpener(DatasetOpener opener) { m_datasetOpener = std::move(opener); }
    std::shared_ptr<Dataset> openDataset(const std::vector<std::string>& paths) const;

    // Replaces the whole state (a loaded session file) and opens its data; undo history is
    // cleared. All or nothing: on error (data missing, frame out of range) nothing changes.
    void replaceState(SessionState state);

    // The open dataset and the current frame (loaded on demand); null without data.
    std::shared_ptr<Dataset> dataset() const { return m_dataset; }
    std::shared_ptr<const Frame> currentFrame();
    // The surfaces that surface.build, the exports and the Python module built in frame
    // `frameIndex` of the open data, so that an export after a build, a second export or a new
    // iso-value within the built range does not build again. It holds one frame's surfaces at
    // most (512 MiB; a movie keeps no more than the frame it draws): asked for another frame or
    // other data, it empties first. The cache's key holds the members, their colours, every
    // field parameter and, for a colour derived from motion, how it was derived
    // (Frame::derivation), so strains derived again never bring old colours back.
    SurfaceCache& surfaceCacheFor(std::size_t frameIndex);
    // The same cache without a frame (its counters; benches clear it to time a whole build).
    SurfaceCache& surfaceCache() { return *m_surfaceCache; }
    // The frame a view shows (its binding applied to the current frame, clamped).
    std::size_t frameOfView(const ViewState& view) const;
    // The reference frame of a view's difference colouring, clamped to the dataset.
    std::size_t referenceFrameOfView(const ViewState& view) const;

    // Visible spheres of the current frame (boxes, thresholds, fault filter).
    const VisibilityResult& visibility();
    // The spheres `boxes`, `thresholds` and the fault filter leave visible in `frame`, from one
    // cache keyed by what they depend on (the frame, the boxes, the thresholds, the filter and
    // the members of the faults it names): the session's own visibility, the workbench's views
    // (with a drag's preview) and its panels ask here, so nothing is worked out twice and no two
    // disagree (issue 39). `key` changes whenever the result may.
    struct Visible {
        std::shared_ptr<const VisibilityResult> result;
        std::uint64_t key = 0;
    };
    Visible visibilityOf(const std::shared_ptr<const Frame>& frame,
                         const std::vector<CuttingBox>& boxes,
                         const std::vector<VariableThreshold>& thresholds);
    // Fault filter as a row mask of `frame` (null when the filter lets everything through).
    std::unique_ptr<std::vector<std::uint8_t>> faultRowMask(const Frame& frame) const;
    // The same for a copy of a state (worker threads).
    static std::unique_ptr<std::vector<std::uint8_t>> faultRowMask(const SessionState& state,
                                                                   const Frame& frame);

    // For op implementations only: the state to change, and the dataset to swap.
    SessionState& mutableState() { return m_state; }
    void setDataset(std::shared_ptr<Dataset> dataset);
    const std::vector<std::string>& dataOverride() const { return m_dataOverride; }
    void touch() { ++m_version; }
    // Runs a state-changing op without journal or undo entry and returns its inverse: for
    // composite ops built from others (fault.merge, fault.candidates).
    Json execute(const Json& cmd);

  private:
    Json run(const Json& cmd, bool& changesState);
    // Hands the state's strains[] to the dataset, so its frames carry their columns.
    void syncDerived();

    SessionState m_state;
    std::string m_note;
    std::string m_moved; // noteMoved's spheres, for the undo label
    std::uint64_t m_version = 1;
    std::shared_ptr<Dataset> m_dataset;
    std::shared_ptr<SurfaceCache> m_surfaceCache;
    std::weak_ptr<Dataset> m_surfaceData; // the data and frame whose surfaces m_surfaceCache holds
    std::size_t m_surfaceFrameIndex = 0;
    std::vector<Json> m_undo;         // inverses, most recent last
    std::uint64_t m_savedVersion = 1; // m_version starts at 1: a new session is unmodified
    // Where in its history the state is: the step on top of the undo stack (each step has a
    // serial), or the start of the history when none. Saved at markSaved().
    std::vector<std::uint64_t> m_undoSerials, m_redoSerials;
    std::uint64_t m_historyStart = 0, m_nextSerial = 1, m_savedPosition = 0;
    std::uint64_t historyPosition() const {
        return m_undoSerials.empty() ? m_historyStart : m_undoSerials.back();
    }
    bool m_markSavedAfterOp = false;
    std::function<bool()> m_interruptCheck;
    std::vector<Json> m_redo;                            // commands that redo, most recent last
    std::vector<std::string> m_undoLabels, m_redoLabels; // describeCommand of each entry
    void checkAction(const Json& cmd) const;

    JournalRecorder m_journal;
    OpRegistry m_ops;
    std::string m_baseDir, m_outputDir;
    FrameSelection m_frameSelection;
    std::vector<std::string> m_dataOverride;
    DatasetOpener m_datasetOpener;

    struct VisibilityEntry {
        // Not held (a cache must not keep frames of millions of spheres past the frame cache's
        // budget): an expired frame's entry matches nothing.
        std::weak_ptr<const Frame> frame;
        std::uint64_t key = 0;
        std::shared_ptr<const VisibilityResult> result;
    };
    std::vector<VisibilityEntry> m_visibilities;           // most recently used last
    std::shared_ptr<const VisibilityResult> m_visibility;  // what visibility() last returned
    std::uint64_t m_filterKey = 0, m_filterKeyVersion = 0; // the fault filter's, per version
    std::uint64_t faultFilterKey();
};

// Built-in ops, grouped by what they change (session_ops_*.cpp).
namespace detail {
void registerDataOps(OpRegistry& ops);
void registerSelectionOps(OpRegistry& ops);
void registerFaultOps(OpRegistry& ops);
void registerOutputOps(OpRegistry& ops);
void registerSurfaceOps(OpRegistry& ops);
void registerSessionOps(OpRegistry& ops);
void registerStrainOps(OpRegistry& ops);
} // namespace detail

} // namespace faultline::core
