#include "core/selection/visibility.hpp"

#include "core/selection/column_view.hpp"
#include "core/selection/row_bits.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <functional>

namespace faultline::core {

namespace {

using detail::FloatBox;
using detail::IntBounds;
using detail::kWordRows;

// 8192 rows per task at least: enough work to pay for a task, small enough to balance.
constexpr std::size_t kGrainWords = 128;

FloatBox toFloatBox(const CuttingBox& box) {
    FloatBox b;
    for (int a = 0; a < 3; ++a) {
        b.min[a] = detail::nearestFloatBound(box.min[a]);
        b.max[a] = detail::nearestFloatBound(box.max[a]);
    }
    return b;
}

std::uint64_t boxWord(const Frame& frame, const FloatBox& box, std::size_t row, std::size_t count) {
    return detail::inBoxWord(frame.x.data() + row, frame.y.data() + row, frame.z.data() + row,
                             count, box);
}

// One threshold bound to its column, with bounds rounded to the column's type.
struct ThresholdTest {
    ColumnView column;
    float floatLo = 0.0f;
    float floatHi = 0.0f;
    IntBounds intBounds;

    std::uint64_t word(std::size_t row, std::size_t count) const {
        if (column.isInteger())
            return intBounds.empty()
                       ? 0
                       : detail::inRangeWord(column.ints + row, count, intBounds.lo, intBounds.hi);
        return detail::inRangeWord(column.floats + row, count, floatLo, floatHi);
    }
};

ThresholdTest makeTest(const ColumnView& column, const VariableThreshold& threshold) {
    ThresholdTest t;
    t.column = column;
    if (column.isInteger())
        t.intBounds = detail::intBoundsFor(threshold.low, threshold.high);
    else {
        t.floatLo = detail::nearestFloatBound(threshold.low);
        t.floatHi = detail::nearestFloatBound(threshold.high);
    }
    return t;
}

void noteMissing(std::vector<std::string>& missing, const std::string& variable) {
    if (std::find(missing.begin(), missing.end(), variable) == missing.end())
        missing.push_back(variable);
}

// The enabled criteria, bound to the frame.
struct Plan {
    std::vector<FloatBox> keeps;
    std::vector<FloatBox> cuts;
    std::vector<ThresholdTest> tests;
};

Plan makePlan(const Frame& frame, std::span<const CuttingBox> boxes,
              std::span<const VariableThreshold> thresholds, std::vector<std::string>& missing) {
    Plan plan;
    for (const CuttingBox& box : boxes)
        if (box.enabled)
            (box.mode == BoxMode::Keep ? plan.keeps : plan.cuts).push_back(toFloatBox(box));
    for (const VariableThreshold& threshold : thresholds) {
        if (!threshold.enabled)
            continue;
        if (auto column = findColumn(frame, threshold.variable)) {
            assert(column->size == frame.size() && "Frame::finalize() checks column sizes");
            plan.tests.push_back(makeTest(*column, threshold));
        } else
            noteMissing(missing, threshold.variable);
    }
    return plan;
}

std::uint64_t rowMaskWord(const std::vector<std::uint8_t>* rowMask, std::size_t row,
                          std::size_t count) {
    return rowMask ? detail::nonZeroWord(rowMask->data() + row, count) : detail::lowBits(count);
}

} // namespace

VisibilityResult computeVisibility(const Frame& frame, std::span<const CuttingBox> boxes,
                                   std::span<const VariableThreshold> thresholds,
                                   const std::vector<std::uint8_t>* rowMask) {
    const std::size_t n = frame.size();
    assert(!rowMask || rowMask->size() == n);
    assert(frame.x.size() == n && frame.y.size() == n && frame.z.size() == n);
    VisibilityResult result;
    const Plan plan = makePlan(frame, boxes, thresholds, result.missingVariables);
    result.mask.resize(n);
    std::uint8_t* mask = result.mask.data();

    result.visibleCount = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, detail::wordCount(n), kGrainWords), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& words, std::size_t visible) {
            for (std::size_t w = words.begin(); w != words.end(); ++w) {
                const std::size_t row = w * kWordRows;
                const std::size_t count = std::min(kWordRows, n - row);
                std::uint64_t bits = rowMaskWord(rowMask, row, count);
                for (const ThresholdTest& test : plan.tests) {
                    if (!bits)
                        break;
                    bits &= test.word(row, count);
                }
                if (bits && !plan.keeps.empty()) {
                    std::uint64_t kept = 0;
                    for (const FloatBox& keep : plan.keeps) {
                        kept |= boxWord(frame, keep, row, count);
                        if ((bits & ~kept) == 0)
                            break; // every row still in play is kept already
                    }
                    bits &= kept;
                }
                for (const FloatBox& cut : plan.cuts) {
                    if (!bits)
                        break;
                    bits &= ~boxWord(frame, cut, row, count);
                }
                detail::expandWord(bits, mask + row, count);
                visible += static_cast<std::size_t>(std::popcount(bits));
            }
            return visible;
        },
        std::plus<>());
    return result;
}

} // namespace faultline::core
