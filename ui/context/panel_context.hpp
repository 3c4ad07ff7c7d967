// What a panel sees of the workbench, by role: PanelContext is the narrow interface panels draw
// with (the Workbench, which composes the panels, implements it), so panels never include the
// workbench and the workbench never needs its panels' insides.
//
// The roles:
//   - the session: read the state, emit commands (applied after the UI of the frame is built,
//     so undo, redo and the journal cover everything), preview a drag without a command;
//   - what the views show this frame (ViewDisplay) and a camera fitted to a box;
//   - services: frames, columns, background jobs, fault surfaces, the renderer;
//   - time: playing, stepping and jumping through frames (Playback);
//   - UI selection (UiSelection): the box and faults picked, the view tool, candidates shown;
//     never part of the session;
//   - chrome: the dock layout, the file dialog, marked widgets, messages, the UI scale.
#pragma once

#include "core/faults/candidates.hpp"
#include "core/session/session.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/context/frame_store.hpp"
#include "ui/context/jobs.hpp"
#include "ui/context/surface_store.hpp"
#include "ui/dock/dock_layout.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/viewport/view_renderer.hpp"
#include "ui/widgets/file_dialog.hpp"
#include "ui/widgets/item_registry.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace faultline::ui {

class PanelContext;

class Panel {
  public:
    virtual ~Panel() = default;
    virtual const char* id() const = 0;
    virtual const char* title() const = 0;
    virtual void draw(PanelContext& ctx) = 0;
    virtual bool padded() const { return true; } // false: content fills the area (viewports)
};

// Where later features plug into existing panels without editing them (the fault analysis
// adds per-fault metric columns and a candidates section to the Faults panel).
struct PanelExtensions {
    struct Section {
        std::string title;
        std::function<void(PanelContext&)> draw;
        bool defaultOpen = false;
    };
    struct FaultColumn {
        std::string title;
        std::function<void(PanelContext&, const core::Fault&)> cell;
    };
    std::vector<Section> faultSections;
    std::vector<FaultColumn> faultColumns;
};

// What one view shows this frame (after previews, frame loading and camera fitting).
struct ViewDisplay {
    std::string name;
    std::size_t wantedFrame = 0;
    std::shared_ptr<const core::Frame> frame; // shown; lags wantedFrame while it loads
    std::size_t shownFrame = 0;
    ModelBounds bounds;     // of the shown frame (centres widened by the largest radius)
    ModelBounds framing;    // what fitting frames: the same without far strays (core/view/framing)
    bool framed = false;    // `framing` is the shown frame's (worked out when a fit needs it)
    double sceneRadius = 1; // half the bounds' diagonal
    std::shared_ptr<const core::VisibilityResult> visibility;
    std::uint64_t visibilityKey = 0;
    core::CameraState camera; // the session's, previewed, fitted when not set yet
    std::array<double, 2> colorRange{0, 1};
    // The column shown instead of the variable's (difference or categories; null: the
    // variable's own, or one colour while a reference frame loads) and what the legend calls it.
    std::shared_ptr<const core::AttributeColumn> colorColumn;
    std::string colorTitle;
    // The view's own variable is in the frame but no sphere has a value of it (incremental
    // strain on a frame with none before it): grey spheres, no legend, and the button says so.
    bool colorHasNoValue = false;
    std::vector<ViewSurface> surfaces; // fault surfaces ready in the shown frame
    std::vector<glm::vec3> palette;    // categories (faults, candidates): colorColumn holds k + 0.5
    std::vector<LegendEntry> legend;   // categories' names and colours, for the legend
    bool loading() const { return !frame || shownFrame != wantedFrame; }
};

// What a left drag in a view does: orbit the camera, or outline spheres to build a fault.
enum class ViewportTool { Orbit, Rectangle, Lasso };

// Playing and scrubbing show frames without a command per frame; pausing commits frame.set.
struct Playback {
    bool playing = false;
    double fps = 5.0;
    bool loop = true;
    int direction = 1;
    std::optional<std::size_t> frame; // shown instead of the session's frame
    double lastStep = 0.0;
};

// What the user has picked in the UI (not part of the session: never saved or journalled).
struct UiSelection {
    std::string box;              // the box the Cutting boxes panel edits
    bool editBoxInView = true;    // its face handles shown in the views
    int activeBoxFace = -1;       // the face handle under the mouse or dragged (0..5)
    std::set<std::string> faults; // picked in the Faults panel
    ViewportTool tool = ViewportTool::Orbit;
    // Rectangle and lasso take the spheres in view (front-most) unless this is set: then every
    // visible sphere whose centre is inside the shape, through the whole depth (OVITO's fence).
    bool throughDepth = false;
    // Candidates found in the Faults panel, shown in their colours in the main view until
    // accepted or cleared (accepting one is a fault.create).
    struct CandidatePreview {
        std::shared_ptr<const core::Frame> frame;
        std::shared_ptr<const core::VisibilityResult> visibility; // of the main view when found
        core::CandidateOptions options;
        core::CandidateSet set;
        std::vector<core::CandidateShape> shapes; // per candidate: orientation, diffuse or not
        CategoryColoring coloring;
    };
    std::optional<CandidatePreview> candidates;
};

class PanelContext {
  public:
    virtual ~PanelContext() = default;

    // ---- the session ----
    // The session is read, never written: changes go through emit(). Its version changes
    // with every command applied.
    virtual std::uint64_t sessionVersion() const = 0;
    virtual const core::SessionState& state() const = 0;
    virtual const std::shared_ptr<core::Dataset>& dataset() const = 0;
    // `onApplied` runs once the command was applied without error.
    virtual void emit(core::Json command, std::function<void()> onApplied) = 0;
    void emit(core::Json command) { emit(std::move(command), {}); }
    // A live edit (box.set, threshold.set/add, camera.set, frame.set) shown this frame only;
    // re-issue it every frame while dragging, emit the command on release.
    virtual void preview(const std::string& key, core::Json command) = 0;

    // ---- what the views show ----
    virtual const std::vector<ViewDisplay>& views() const = 0;
    virtual const ViewDisplay* view(const std::string& name) const = 0;
    // The frame the main view shows and its visibility (histograms, data panel).
    virtual const ViewDisplay* mainDisplay() const = 0;
    virtual std::size_t displayFrame() const = 0; // the current frame, or the one playing
    // A view's camera turned to show [lo, hi] whole in its image, beside its legend.
    virtual core::CameraState fitCamera(const core::ViewState& view, core::CameraState camera,
                                        const std::array<double, 3>& lo,
                                        const std::array<double, 3>& hi) const = 0;
    // Boxes as shown (the session's with a drag's preview applied).
    virtual const std::vector<core::CuttingBox>& displayBoxes() const = 0;

    // ---- services ----
    virtual FrameStore& frames() = 0;
    virtual ColumnCatalog& columns() = 0;
    virtual JobRunner& jobs() = 0;
    virtual SurfaceStore& surfaces() = 0;
    virtual ViewRenderer* renderer() const = 0;
    // The memory frames may take (0: a quarter of RAM), remembered with the recent files.
    virtual std::size_t frameMemoryBudget() const = 0;
    virtual void setFrameMemoryBudget(std::size_t bytes) = 0;

    // ---- time ----
    virtual Playback& playback() = 0;
    virtual void play() = 0;
    virtual void pause() = 0; // commits the frame shown
    virtual void stepFrames(long long delta) = 0;
    virtual void jumpToFrame(long long frame) = 0;

    // ---- UI selection ----
    virtual UiSelection& selection() = 0;

    // ---- chrome ----
    virtual DockLayout& layout() = 0;
    virtual void commitLayout() = 0; // emits layout.set when the layout differs from the session's
    virtual FileDialog& fileDialog() = 0;
    // Where export dialogs open: the last export's folder, else the session's, else the data's
    // (the launch folder for the built-in demo).
    virtual std::string exportFolder() const = 0;
    virtual ItemRegistry& items() = 0;
    void mark(const std::string& name) { items().markLastItem(name); }
    virtual PanelExtensions& extensions() = 0;
    virtual double now() const = 0;
    virtual float scale() const = 0;
    virtual void info(std::string text) = 0;
    virtual void error(std::string text) = 0;
};

} // namespace faultline::ui
