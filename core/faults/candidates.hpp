// Fault candidates: connected components of the visible spheres of a frame, two spheres being
// neighbours when |c_i - c_j| < link * (r_i + r_j). Largest first; the user accepts them as faults.
#pragma once

#include "core/faults/fault.hpp"
#include "core/model/frame.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace faultline::core {

// Defaults of the journal's fault.candidates, shared by export.csv fault_tracks and the Faults
// panel: link k, smallest candidate kept, names prefix + "1".."n".
inline constexpr double kDefaultCandidateLink = 1.1;
inline constexpr std::size_t kDefaultCandidateMinSize = 10;
inline constexpr std::string_view kDefaultCandidatePrefix = "C";

struct CandidateOptions {
    double link = kDefaultCandidateLink; // k: neighbours when distance < k (r_i + r_j); > 0
    std::size_t minSize = 1;             // components with fewer spheres are dropped
};

struct Candidate {
    std::vector<std::int64_t> ids; // particle ids, sorted ascending
    std::size_t size() const { return ids.size(); }
};

struct CandidateSet {
    // Sorted by size, largest first; equal sizes by smallest member id, ascending. The order
    // does not depend on the row order of the frame or on threading.
    std::vector<Candidate> candidates;
    // Per frame row: index into `candidates`, or -1 (hidden, or in a component below minSize).
    std::vector<std::int32_t> rowLabel;
};

// Components of the spheres whose visible[row] != 0 (visible.size() == frame.size(), asserted).
// A sphere with a non-finite centre or radius has no neighbours. Uniform cell grid (cell =
// the largest neighbour distance among visible spheres), lock-free union-find, parallel (TBB).
// Throws std::invalid_argument when options.link is not a finite number > 0.
CandidateSet findCandidates(const Frame& frame, std::span<const std::uint8_t> visible,
                            const CandidateOptions& options = {});

// The n-th of a sequence of distinct colours (golden-angle hues), for showing candidates.
std::array<float, 3> candidateColor(std::size_t index);

// The journal's `fault.candidates` acceptance: faults named prefix + "1".."n" (largest first),
// coloured candidateColor(i), empty notes, visible. Name clashes are the caller's to resolve.
std::vector<Fault> faultsFromCandidates(std::span<const Candidate> candidates,
                                        std::string_view prefix);

} // namespace faultline::core
