// ViewComposer: the workbench's display composition. Each UI frame it works out what every view
// shows (ViewDisplay): the frame it binds to (loaded in the background), the boxes and
// thresholds with a drag's preview applied (through the session's own ops on a copy), the
// visible spheres, the camera (fitted while unset), the colours (a variable, a difference since
// a frame, or categories) and the fault surfaces ready in that frame. It keeps what is costly
// to work out again: visibilities, fault colourings, difference columns, all-frames ranges.
#pragma once

#include "core/model/difference_column_cache.hpp"
#include "core/session/session.hpp"
#include "ui/context/panel_context.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace faultline::ui {

class ViewComposer {
  public:
    ViewComposer(core::Session& session, FrameStore& frames, SurfaceStore& surfaces,
                 JobRunner& jobs);

    // What the views show after this frame's previews, with frame `base` as the current one.
    struct Inputs {
        const std::map<std::string, core::Json>& previews;
        std::size_t base = 0;
        double now = 0.0;
        const UiSelection& selection;
        // A view's camera fitted to its bounds, beside its legend (Workbench::fitCamera).
        std::function<core::CameraState(const core::ViewState&, const ViewDisplay&,
                                        core::CameraState)>
            fit;
    };
    void update(const Inputs& in);
    // Forgets everything kept for the data (another dataset was opened).
    void reset();

    const std::vector<ViewDisplay>& views() const { return m_views; }
    const ViewDisplay* view(const std::string& name) const;
    const std::vector<core::CuttingBox>& displayBoxes() const { return m_displayBoxes; }
    const std::vector<core::VariableThreshold>& displayThresholds() const {
        return m_displayThresholds;
    }

  private:
    void resolveColors(const core::ViewState& view, ViewDisplay& d, std::size_t channel,
                       const UiSelection& selection);
    // The colour range over every frame of the data, as figures and movies take it
    // (core::colorRangeOverFrames), worked out in the background; nothing until it is ready.
    std::optional<std::array<double, 2>> exactAllFramesRange(const core::ViewState& view);
    const CategoryColoring* categoriesFor(const core::ViewState& view, const ViewDisplay& d,
                                          const UiSelection& selection);

    core::Session& m_session;
    FrameStore& m_frames;
    SurfaceStore& m_surfaces;
    core::DifferenceColumnCache m_differences;
    std::vector<ViewDisplay> m_views;
    std::vector<core::CuttingBox> m_displayBoxes;
    std::vector<core::VariableThreshold> m_displayThresholds;
    JobRunner& m_jobs;
    std::map<std::string, std::array<double, 2>> m_allFramesRange; // by variable: frames seen
    // Issue 41: the live view's "all frames" range was the frames seen so far while figures
    // took every frame, so the legends differed until each frame had been shown.
    struct ExactRange {
        std::shared_ptr<Job> job;
        std::optional<std::array<double, 2>> range; // set when the job is done
        bool ready = false;
    };
    std::map<std::string, std::shared_ptr<ExactRange>> m_exactRanges; // by what they depend on
    struct VisibleRangeEntry { // a variable's range over a view's visible spheres
        std::shared_ptr<const core::VisibilityResult> visibility;
        std::string variable;
        bool percentiles = false; // the 1st to 99th percentile rather than min to max
        std::optional<std::pair<double, double>> range;
    };
    std::vector<VisibleRangeEntry> m_visibleRanges; // the views' latest, a few at most
    bool hasNoValue(const std::shared_ptr<const core::Frame>& frame, const std::string& variable);
    struct NoValueEntry {
        std::weak_ptr<const core::Frame> frame;
        std::string variable;
        bool none = false;
    };
    std::vector<NoValueEntry> m_noValue; // frames' columns without a value, a few at most
    struct FaultColoringEntry {
        std::shared_ptr<const core::Frame> frame;
        std::uint64_t key = 0;
        CategoryColoring coloring;
    };
    std::vector<FaultColoringEntry> m_faultColorings;
    std::uint64_t m_faultsKey = 0, m_faultsKeyVersion = ~0ull; // at a session version
};

} // namespace faultline::ui
