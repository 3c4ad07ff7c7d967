// Visibility: which spheres of a frame pass the cutting boxes, variable thresholds and an
// optional row mask (fault filters), as one byte per row plus the count. Rules: JOURNAL.md.
//
// A sphere is visible when all hold (bounds inclusive, NaN never passes a threshold):
//   - no enabled keep box exists, or its centre lies in at least one enabled keep box;
//   - its centre lies in no enabled cut box;
//   - low <= value <= high for every enabled threshold whose variable the frame has;
//   - rowMask[row] != 0, when a row mask is given (the caller's fault filter).
// Disabled boxes and thresholds have no effect. An enabled threshold on a variable the frame
// lacks is ignored and named in `missingVariables` (a journal made on other data can warn).
// Variables are attribute columns, or the built-in x, y, z, radius (see column_view.hpp).
//
// Design (measured in bench/bench_selection.cpp, 1,000,000 spheres, 2 threads):
//   Each criterion is evaluated 64 rows at a time into one bit word (SSE2 compares + movemask,
//   row_bits.hpp). Box and threshold bounds are first rounded inwards to float (int for
//   integer columns) so the float compare equals the exact double compare of the contract.
//   - computeVisibility(): a stateless fused parallel pass; per 64-row word it ANDs every
//     criterion and skips the rest of a word's criteria once it is all zero. Reads every
//     criterion column each time.
//   - VisibilityEvaluator: keeps one bit vector per criterion (n/8 bytes each), keyed by the
//     frame's identity (its shared_ptr owner) and the criterion's rounded bounds. enabled and
//     mode are not part of a key, so toggling a box or threshold, or changing its mode, costs
//     only the recombine. After one threshold change it reads that column once and ANDs the
//     cached words, then expands to bytes: the interactive path (see the bench for figures).
//   The row mask is never cached (its contents may change behind the same pointer); it is read
//   in every recombine.
#pragma once

#include "core/model/frame.hpp"
#include "core/selection/cutting_box.hpp"
#include "core/selection/variable_threshold.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace faultline::core {

struct VisibilityResult {
    std::vector<std::uint8_t> mask; // one byte per row: 1 visible, 0 hidden
    std::size_t visibleCount = 0;
    std::vector<std::string> missingVariables; // enabled thresholds ignored, in order, unique
};

// One fused parallel pass, nothing cached. rowMask, when given, must have frame.size() bytes
// (nonzero = allowed).
VisibilityResult computeVisibility(const Frame& frame, std::span<const CuttingBox> boxes,
                                   std::span<const VariableThreshold> thresholds,
                                   const std::vector<std::uint8_t>* rowMask = nullptr);

// The same result, recomputing only the criteria that changed since the previous call.
// Holds one frame at a time (a weak reference: it never keeps a frame alive); a different frame
// drops the cache. Frames must not be modified while cached (Dataset frames are const).
// Not thread-safe: use one evaluator per view; evaluate() itself runs in parallel (TBB).
class VisibilityEvaluator {
  public:
    VisibilityEvaluator();
    ~VisibilityEvaluator();
    VisibilityEvaluator(VisibilityEvaluator&&) noexcept;
    VisibilityEvaluator& operator=(VisibilityEvaluator&&) noexcept;

    // The result stays valid until the next evaluate() or clear().
    const VisibilityResult& evaluate(const std::shared_ptr<const Frame>& frame,
                                     std::span<const CuttingBox> boxes,
                                     std::span<const VariableThreshold> thresholds,
                                     const std::vector<std::uint8_t>* rowMask = nullptr);
    const VisibilityResult& result() const { return m_result; }

    // Drops the cached criteria and the result.
    void clear();

    // What the last evaluate() did: criteria evaluated over the frame vs taken from the cache.
    std::size_t lastComputed() const { return m_lastComputed; }
    std::size_t lastReused() const { return m_lastReused; }
    // Bytes held by the cached criterion bits.
    std::size_t cacheBytes() const;

  private:
    struct Cache;
    std::unique_ptr<Cache> m_cache;
    VisibilityResult m_result;
    std::size_t m_lastComputed = 0;
    std::size_t m_lastReused = 0;
};

} // namespace faultline::core
