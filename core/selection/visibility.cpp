#include "core/selection/visibility.hpp"

#include "core/selection/column_view.hpp"
#include "core/selection/row_bits.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <functional>
#include <optional>

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
        b.min[a] = detail::ceilToFloat(box.min[a]);
        b.max[a] = detail::floorToFloat(box.max[a]);
    }
    return b;
}

std::uint64_t boxWord(const Frame& frame, const FloatBox& box, std::size_t row,
                      std::size_t count) {
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
            return intBounds.empty() ? 0
                                     : detail::inRangeWord(column.ints + row, count,
                                                           intBounds.lo, intBounds.hi);
        return detail::inRangeWord(column.floats + row, count, floatLo, floatHi);
    }
    // Same column and same rounded bounds: the same bits. NaN bounds never match (recomputed).
    bool sameAs(const ThresholdTest& o) const {
        if (column.floats != o.column.floats || column.ints != o.column.ints)
            return false;
        if (column.isInteger())
            return intBounds.lo == o.intBounds.lo && intBounds.hi == o.intBounds.hi;
        return floatLo == o.floatLo && floatHi == o.floatHi;
    }
};

ThresholdTest makeTest(const ColumnView& column, const VariableThreshold& threshold) {
    ThresholdTest t;
    t.column = column;
    if (column.isInteger())
        t.intBounds = detail::intBoundsFor(threshold.low, threshold.high);
    else {
        t.floatLo = detail::ceilToFloat(threshold.low);
        t.floatHi = detail::floorToFloat(threshold.high);
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
              std::span<const VariableThreshold> thresholds,
              std::vector<std::string>& missing) {
    Plan plan;
    for (const CuttingBox& box : boxes)
        if (box.enabled)
            (box.mode == BoxMode::Keep ? plan.keeps : plan.cuts).push_back(toFloatBox(box));
    for (const VariableThreshold& threshold : thresholds) {
        if (!threshold.enabled)
            continue;
        if (auto column = findColumn(frame, threshold.variable))
            plan.tests.push_back(makeTest(*column, threshold));
        else
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

// ---------------------------------------------------------------------------------------------

struct VisibilityEvaluator::Cache {
    struct BoxBits {
        FloatBox box;
        std::vector<std::uint64_t> bits;
        bool ready = false; // bits hold the test over the whole frame
    };
    struct ThresholdBits {
        ThresholdTest test;
        std::vector<std::uint64_t> bits;
        bool ready = false;
    };
    std::weak_ptr<const Frame> frameOwner;
    const Frame* frame = nullptr;
    std::vector<BoxBits> boxes;
    std::vector<ThresholdBits> thresholds;

    bool holds(const std::shared_ptr<const Frame>& f) const {
        return frame == f.get() && !frameOwner.owner_before(f) && !f.owner_before(frameOwner);
    }
};

VisibilityEvaluator::VisibilityEvaluator() : m_cache(std::make_unique<Cache>()) {}
VisibilityEvaluator::~VisibilityEvaluator() = default;
VisibilityEvaluator::VisibilityEvaluator(VisibilityEvaluator&&) noexcept = default;
VisibilityEvaluator& VisibilityEvaluator::operator=(VisibilityEvaluator&&) noexcept = default;

void VisibilityEvaluator::clear() {
    *m_cache = Cache{};
    m_result = VisibilityResult{};
    m_lastComputed = m_lastReused = 0;
}

std::size_t VisibilityEvaluator::cacheBytes() const {
    std::size_t bytes = 0;
    for (const auto& b : m_cache->boxes)
        bytes += b.bits.capacity() * sizeof(std::uint64_t);
    for (const auto& t : m_cache->thresholds)
        bytes += t.bits.capacity() * sizeof(std::uint64_t);
    return bytes;
}

const VisibilityResult& VisibilityEvaluator::evaluate(const std::shared_ptr<const Frame>& framePtr,
                                                      std::span<const CuttingBox> boxes,
                                                      std::span<const VariableThreshold> thresholds,
                                                      const std::vector<std::uint8_t>* rowMask) {
    assert(framePtr);
    const Frame& frame = *framePtr;
    const std::size_t n = frame.size();
    const std::size_t nWords = detail::wordCount(n);
    assert(!rowMask || rowMask->size() == n);

    Cache& cache = *m_cache;
    if (!cache.holds(framePtr)) {
        cache = Cache{};
        cache.frameOwner = framePtr;
        cache.frame = framePtr.get();
    }
    m_result.missingVariables.clear();
    m_lastComputed = m_lastReused = 0;

    // The new cache: one entry per distinct criterion that is enabled now or was cached before
    // (so toggling enabled back costs nothing). Entries not ready are computed below.
    std::vector<Cache::BoxBits> newBoxes;
    std::vector<Cache::ThresholdBits> newThresholds;
    std::vector<std::size_t> keepIdx, cutIdx, testIdx;

    for (const CuttingBox& box : boxes) {
        const FloatBox key = toFloatBox(box);
        auto same = [&](const Cache::BoxBits& e) { return e.box == key; };
        auto it = std::find_if(newBoxes.begin(), newBoxes.end(), same);
        if (it == newBoxes.end()) {
            auto old = std::find_if(cache.boxes.begin(), cache.boxes.end(), same);
            if (old != cache.boxes.end()) {
                newBoxes.push_back(std::move(*old));
                cache.boxes.erase(old);
                ++m_lastReused;
            } else if (box.enabled) {
                newBoxes.push_back({key, {}, false});
            } else {
                continue; // disabled and not cached: not needed
            }
            it = newBoxes.end() - 1;
        }
        if (box.enabled)
            (box.mode == BoxMode::Keep ? keepIdx : cutIdx)
                .push_back(static_cast<std::size_t>(it - newBoxes.begin()));
    }
    for (const VariableThreshold& threshold : thresholds) {
        const auto column = findColumn(frame, threshold.variable);
        if (!column) {
            if (threshold.enabled)
                noteMissing(m_result.missingVariables, threshold.variable);
            continue;
        }
        const ThresholdTest test = makeTest(*column, threshold);
        auto same = [&](const Cache::ThresholdBits& e) { return e.test.sameAs(test); };
        auto it = std::find_if(newThresholds.begin(), newThresholds.end(), same);
        if (it == newThresholds.end()) {
            auto old = std::find_if(cache.thresholds.begin(), cache.thresholds.end(), same);
            if (old != cache.thresholds.end()) {
                newThresholds.push_back(std::move(*old));
                cache.thresholds.erase(old);
                ++m_lastReused;
            } else if (threshold.enabled) {
                newThresholds.push_back({test, {}, false});
            } else {
                continue;
            }
            it = newThresholds.end() - 1;
        }
        if (threshold.enabled)
            testIdx.push_back(static_cast<std::size_t>(it - newThresholds.begin()));
    }

    // Storage first (so pointers below stay put), then the list of what to compute.
    std::vector<Cache::BoxBits*> boxesToCompute;
    std::vector<Cache::ThresholdBits*> testsToCompute;
    for (auto& e : newBoxes) {
        if (!e.ready) {
            e.bits.resize(nWords);
            boxesToCompute.push_back(&e);
        }
    }
    for (auto& e : newThresholds) {
        if (!e.ready) {
            e.bits.resize(nWords);
            testsToCompute.push_back(&e);
        }
    }
    m_lastComputed = boxesToCompute.size() + testsToCompute.size();

    std::vector<const std::uint64_t*> keeps, cuts, tests;
    for (std::size_t i : keepIdx)
        keeps.push_back(newBoxes[i].bits.data());
    for (std::size_t i : cutIdx)
        cuts.push_back(newBoxes[i].bits.data());
    for (std::size_t i : testIdx)
        tests.push_back(newThresholds[i].bits.data());

    m_result.mask.resize(n);
    std::uint8_t* mask = m_result.mask.data();
    m_result.visibleCount = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, nWords, kGrainWords), std::size_t{0},
        [&](const tbb::blocked_range<std::size_t>& words, std::size_t visible) {
            for (std::size_t w = words.begin(); w != words.end(); ++w) {
                const std::size_t row = w * kWordRows;
                const std::size_t count = std::min(kWordRows, n - row);
                for (Cache::BoxBits* e : boxesToCompute)
                    e->bits[w] = boxWord(frame, e->box, row, count);
                for (Cache::ThresholdBits* e : testsToCompute)
                    e->bits[w] = e->test.word(row, count);

                std::uint64_t bits = rowMaskWord(rowMask, row, count);
                for (const std::uint64_t* t : tests)
                    bits &= t[w];
                if (!keeps.empty()) {
                    std::uint64_t kept = 0;
                    for (const std::uint64_t* k : keeps)
                        kept |= k[w];
                    bits &= kept;
                }
                for (const std::uint64_t* c : cuts)
                    bits &= ~c[w];
                detail::expandWord(bits, mask + row, count);
                visible += static_cast<std::size_t>(std::popcount(bits));
            }
            return visible;
        },
        std::plus<>());

    for (Cache::BoxBits* e : boxesToCompute)
        e->ready = true;
    for (Cache::ThresholdBits* e : testsToCompute)
        e->ready = true;
    cache.boxes = std::move(newBoxes);
    cache.thresholds = std::move(newThresholds);
    return m_result;
}

} // namespace faultline::core
