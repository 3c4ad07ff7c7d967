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
// Design: each criterion is evaluated 64 rows at a time into one bit word (SSE2 compares and
// movemask, row_bits.hpp), ANDed per word, then expanded to bytes; TBB splits the words. A
// word's remaining criteria are skipped once it is all zero. Box and threshold bounds are first
// rounded inwards to float (to int for integer columns), so the float compare equals the exact
// double compare of the contract. Nothing is cached: callers keep the result per (frame, state
// version). Measured (bench/bench_selection.cpp, 10^6 spheres, 2 keep/cut boxes and 6
// thresholds, 2 threads): about 1.1 ms per recompute, so a per-criterion bit cache, which
// did one threshold change in 0.21 ms (git 35ab3b4, VisibilityEvaluator), was not kept: the
// simple pass already meets the 4 ms target with room, and has no cache to invalidate.
#pragma once

#include "core/model/frame.hpp"
#include "core/selection/cutting_box.hpp"
#include "core/selection/variable_threshold.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace faultline::core {

struct VisibilityResult {
    std::vector<std::uint8_t> mask; // one byte per row: 1 visible, 0 hidden
    std::size_t visibleCount = 0;
    std::vector<std::string> missingVariables; // enabled thresholds ignored, in order, unique
};

// One fused parallel pass (TBB). rowMask, when given, must have frame.size() bytes
// (nonzero = allowed).
VisibilityResult computeVisibility(const Frame& frame, std::span<const CuttingBox> boxes,
                                   std::span<const VariableThreshold> thresholds,
                                   const std::vector<std::uint8_t>* rowMask = nullptr);

} // namespace faultline::core
