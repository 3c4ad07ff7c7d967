// What a view's spheres are coloured by in a frame, and over which range: the one rule the
// workbench's live views, `render` figures and movies share (issue 39: it was worked out twice,
// in ui/workbench/view_composer and ui/viewport/session_figure, and the two had drifted).
//   - a difference (change of the variable, or displacement) since the view's reference frame:
//     its column, titled "strain change since frame 10"; the range over every frame (a change
//     symmetric about zero, a displacement from 0) unless the range is fixed;
//   - else the variable's own column: "this frame's" range over the spheres shown (thresholds,
//     boxes and faults hide the rest), "percentile" the 1st to 99th percentile of those spheres
//     (a few extremes, grains thrown out of a model, leave the rest their colours), "all
//     frames" over every frame, or the fixed range;
//   - a range of one value is widened by 0.5 either way, a range with no value is [0, 1].
// Categories (the "faults" colouring, candidates) are the callers': they are palettes, not
// ranges. What is slow (frames, difference columns, ranges over every frame) comes from
// ViewColorSources: the workbench answers from its caches and background jobs (nothing yet:
// one colour, or the range seen so far), a figure computes it there and then.
#pragma once

#include "core/color/colormap.hpp"
#include "core/model/frame.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/session_state.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace faultline::core {

struct ViewColoring {
    // Shown in place of the variable's own column: a difference since `reference` (null: the
    // variable's own column, or one colour when `title` is empty).
    std::shared_ptr<const AttributeColumn> column;
    std::string title;                    // what the legend calls the colours; empty: one colour
    std::optional<std::size_t> reference; // a difference's reference frame
    ValueRange range{0, 1};
};

struct ViewColorSources {
    // Frame `index` of the data; null while it loads (a difference then shows one colour).
    std::function<std::shared_ptr<const Frame>(std::size_t index)> frame;
    // The change of `variable` (Mode::Change) or the displacement of `now` since `reference`.
    // May throw std::invalid_argument (the frames lack the variable: one colour).
    std::function<std::shared_ptr<const AttributeColumn>(
        const std::shared_ptr<const Frame>& now, const std::shared_ptr<const Frame>& reference,
        ColorDifference::Mode mode, const std::string& variable)>
        difference;
    // The range over every frame of what `view` colours by (colorRangeOverFrames), given its
    // range in this frame and its legend title; the workbench answers with the range of the
    // frames seen so far until the whole run's is worked out.
    std::function<ValueRange(const ViewState& view, const std::string& title, ValueRange inFrame)>
        allFrames;
    // `variable`'s range over the spheres `visibility` shows (`percentiles`: from its 1st to its
    // 99th percentile there, maskedQuantiles); nullopt without a finite value.
    std::function<std::optional<ValueRange>(const Frame& frame, const VisibilityResult& visibility,
                                            const std::string& variable, bool percentiles)>
        visibleRange;
};

// The colours of `view` showing frame `shown` (of `frameCount`), `frame` with `visibility`.
ViewColoring colorView(const ViewState& view, std::size_t shown, std::size_t frameCount,
                       const std::shared_ptr<const Frame>& frame,
                       const VisibilityResult* visibility, const ViewColorSources& sources);

} // namespace faultline::core
