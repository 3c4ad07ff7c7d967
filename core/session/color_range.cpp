#include "core/session/color_range.hpp"

#include "core/model/frame_difference.hpp"
#include "core/selection/column_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace faultline::core {

ValueRange symmetricAboutZero(ValueRange range) {
    const double m = std::max(std::fabs(range.low), std::fabs(range.high));
    return {-m, m};
}

std::optional<ValueRange> differenceRangeOverFrames(const Dataset& dataset, const ViewState& view,
                                                    std::vector<std::size_t> frames) {
    if (view.difference.mode == ColorDifference::Mode::None || dataset.frameCount() == 0)
        return std::nullopt;
    if (frames.empty()) {
        frames.resize(dataset.frameCount());
        std::iota(frames.begin(), frames.end(), std::size_t{0});
    }
    double lo = 1e300, hi = -1e300;
    for (std::size_t k : frames) {
        if (k >= dataset.frameCount())
            continue;
        const std::size_t ref = referenceFrame(view, k, dataset.frameCount());
        const auto now = dataset.frame(k), before = dataset.frame(ref);
        AttributeColumn column;
        try {
            column = view.difference.mode == ColorDifference::Mode::Change
                         ? variableChange(*now, *before, view.colorVariable)
                         : displacementSince(*now, *before);
        } catch (const std::invalid_argument&) {
            continue; // the frame lacks the variable
        }
        bool any = false;
        for (float v : column.floats)
            if (std::isfinite(v)) {
                any = true;
                break;
            }
        if (!any)
            continue;
        lo = std::min(lo, column.min);
        hi = std::max(hi, column.max);
    }
    if (!(lo <= hi))
        return std::nullopt;
    if (view.difference.mode == ColorDifference::Mode::Change)
        return symmetricAboutZero({lo, hi});
    return ValueRange{0.0, hi};
}

std::optional<ValueRange> colorRangeOverFrames(const Dataset& dataset, const ViewState& view,
                                               const std::vector<std::size_t>& frames) {
    if (view.difference.mode != ColorDifference::Mode::None)
        return differenceRangeOverFrames(dataset, view, frames);
    if (view.colorVariable.empty())
        return std::nullopt;
    double lo = 1e300, hi = -1e300;
    const bool percentiles = view.rangeMode == RangeMode::Percentile;
    std::vector<std::uint8_t> every;
    auto take = [&](std::size_t k) {
        const auto frame = dataset.frame(k);
        if (percentiles) {
            every.assign(frame->size(), 1);
            if (const auto q = maskedQuantiles(*frame, view.colorVariable, every, 0.01, 0.99))
                lo = std::min(lo, q->first), hi = std::max(hi, q->second);
        } else if (const auto r = variableRange(*frame, view.colorVariable)) {
            lo = std::min(lo, r->low), hi = std::max(hi, r->high);
        }
    };
    if (frames.empty())
        for (std::size_t k = 0; k < dataset.frameCount(); ++k)
            take(k);
    for (std::size_t k : frames)
        if (k < dataset.frameCount())
            take(k);
    return lo <= hi ? std::optional(ValueRange{lo, hi}) : std::nullopt;
}

} // namespace faultline::core
