#include "core/session/view_colors.hpp"

#include "core/selection/column_view.hpp"
#include "core/session/color_range.hpp"

#include <cmath>
#include <stdexcept>

namespace faultline::core {

namespace {

ValueRange widened(ValueRange r) {
    if (!std::isfinite(r.low) || !std::isfinite(r.high) || r.low > r.high)
        return {0, 1};
    if (r.low == r.high)
        return {r.low - 0.5, r.high + 0.5};
    return r;
}

} // namespace

ViewColoring colorView(const ViewState& view, std::size_t shown, std::size_t frameCount,
                       const std::shared_ptr<const Frame>& frame,
                       const VisibilityResult* visibility, const ViewColorSources& sources) {
    ViewColoring c;
    if (!frame)
        return c;
    using Mode = ColorDifference::Mode;
    ValueRange range{0, 1};
    c.title = view.colorVariable;
    if (view.difference.mode != Mode::None) {
        const std::size_t ref = referenceFrame(view, shown, frameCount);
        c.title.clear(); // one colour until the reference frame is here
        if (auto refFrame = sources.frame(ref)) {
            try {
                c.column =
                    sources.difference(frame, refFrame, view.difference.mode, view.colorVariable);
            } catch (const std::invalid_argument&) {
                c.column.reset(); // the frames lack the variable: one colour
            }
            if (c.column) {
                c.title = colorTitle(view, ref);
                c.reference = ref;
                if (c.column->min <= c.column->max)
                    range = {c.column->min, c.column->max};
            }
        }
    } else if (!view.colorVariable.empty()) {
        if (const auto r = variableRange(*frame, view.colorVariable))
            range = {r->low, r->high};
    }
    const RangeMode mode = effectiveRangeMode(view);
    if (!c.title.empty() && mode == RangeMode::AllFrames) {
        range = sources.allFrames(view, c.title, range);
        // Issue 41: zero change keeps the map's middle colour at every frame; a displacement
        // starts at 0.
        if (view.difference.mode == Mode::Change)
            range = symmetricAboutZero(range);
        else if (view.difference.mode == Mode::Displacement)
            range.low = 0.0;
    }
    // Issue 41: "this frame's min to max" spans the spheres the view shows, not those that
    // thresholds, boxes or the faults shown hide.
    if (mode == RangeMode::CurrentFrame && !view.colorVariable.empty() && visibility &&
        visibility->visibleCount > 0 && visibility->visibleCount < frame->size())
        if (const auto r = sources.visibleRange(*frame, *visibility, view.colorVariable, false))
            range = *r;
    // The percentiles of the spheres shown (all of them too: the frame's own range is min to
    // max). Until the visibility is known, the frame's min to max.
    if (mode == RangeMode::Percentile && !view.colorVariable.empty() && visibility &&
        visibility->visibleCount > 0)
        if (const auto r = sources.visibleRange(*frame, *visibility, view.colorVariable, true))
            range = *r;
    if (view.rangeMode == RangeMode::Fixed)
        range = {view.range[0], view.range[1]};
    c.range = widened(range);
    return c;
}

} // namespace faultline::core
