// FrameLoader: how the fault analyses reach the frames of a time series without holding them all.
// Dataset::frame fits (bind it in a lambda); it must be safe to call from several threads.
#pragma once

#include "core/model/frame.hpp"

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace faultline::core {

using FrameLoader = std::function<std::shared_ptr<const Frame>(std::size_t frame)>;

// The frames that per-frame work (metrics, tracks, events, per-frame renders) covers:
// `faultline replay --frames A:B` (inclusive) and `--shard K/N` (every N-th frame, from frame
// K-1). Work that needs other frames (a seed's first break, a fault's first appearance, the frame
// before an event) reads them, so results do not depend on how a run is split.
struct FrameSelection {
    std::size_t first = 0;
    std::size_t last = std::numeric_limits<std::size_t>::max(); // inclusive
    std::size_t shard = 0;                                      // 0-based: f % shards == shard
    std::size_t shards = 1;

    bool everything() const {
        return first == 0 && last == std::numeric_limits<std::size_t>::max() && shards == 1;
    }
    bool contains(std::size_t f) const { return f >= first && f <= last && f % shards == shard; }
    // The selected frames below frameCount, ascending.
    std::vector<std::size_t> frames(std::size_t frameCount) const;
    // "frames 3..9", "shard 2/4", "frames 3..9, shard 2/4" or "every frame".
    std::string describe() const;
    bool operator==(const FrameSelection&) const = default;
};

// "A:B" (A <= B) and "K/N" (1 <= K <= N); std::invalid_argument saying what was expected.
FrameSelection parseFrameRange(const std::string& text);
FrameSelection parseFrameShard(const std::string& text);

} // namespace faultline::core
