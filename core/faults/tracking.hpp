// Fault tracking: labels follow particle ids across frames, and in each frame a fault is also
// re-detected as the candidate sharing most ids with it, giving its membership through time.
#pragma once

#include "core/faults/candidates.hpp"
#include "core/faults/fault.hpp"
#include "core/faults/frame_loader.hpp"
#include "core/faults/metrics.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace faultline::core {

// Rows of the ids present in this frame, in the order of `ids` (absent ids are skipped).
std::vector<std::uint32_t> memberRows(const Frame& frame, std::span<const std::int64_t> ids);

// How one fault meets one frame's candidates.
struct CandidateMatch {
    std::size_t present = 0;     // fault ids present in the frame (the label, following ids)
    std::int32_t candidate = -1; // index into the frame's CandidateSet; -1 when none shares an id
    std::size_t candidateSize = 0;
    std::size_t shared = 0; // present fault ids inside that candidate
    double jaccard = 0;     // shared / (present + candidateSize - shared); 0 without a match
    double precision = 0;   // shared / candidateSize: how much of the candidate is the fault
    double recall = 0;      // shared / present: how much of the fault the candidate holds
    bool operator==(const CandidateMatch&) const = default;
};

// For each fault, the candidate with the most shared ids (ties: the lower candidate index,
// i.e. the larger candidate). `candidates` must come from findCandidates on this frame.
std::vector<CandidateMatch> matchFaults(const Frame& frame, const CandidateSet& candidates,
                                        std::span<const Fault> faults);

struct FaultTrackPoint {
    std::size_t frame = 0;
    CandidateMatch match;
    std::vector<std::int64_t> members; // the matched candidate's ids, when asked for
};

// One per fault, one point per frame in order 0..frameCount-1.
struct FaultTrack {
    std::vector<FaultTrackPoint> points;
};

// The visible mask of a frame (size frame.size()), as the session's boxes and thresholds say.
using VisibleMaskFn = std::function<std::vector<std::uint8_t>(const Frame&, std::size_t frame)>;

// Candidates of every frame (from its visible mask) matched against every fault. Frames are
// visited one at a time (candidate search is parallel inside). keepMembers stores each
// matched candidate's ids (memory: faults x frames x candidate size).
// With a selection, only its frames (the points are those frames, in order).
std::vector<FaultTrack> trackFaults(std::size_t frameCount, const FrameLoader& load,
                                    const VisibleMaskFn& visibleMask, std::span<const Fault> faults,
                                    const CandidateOptions& options = {}, bool keepMembers = false,
                                    const FrameSelection& selection = {});

// A frame's candidates: findCandidates on its visible mask, or a cache of earlier results
// (the workbench keeps them while the thresholds and boxes stay, so following other faults
// does not search every frame again).
using CandidatesFn =
    std::function<std::shared_ptr<const CandidateSet>(const Frame&, std::size_t frame)>;
CandidatesFn candidatesOfVisible(const VisibleMaskFn& visibleMask, const CandidateOptions& options);

// Growth: each fault's metrics frame by frame on what the fault is in that frame, the candidate
// that matches it (as trackFaults), not its fixed members; where no candidate matches, the row
// has count 0 and undefined values. Rows and seeds as computeMetricsSeries gives them. With
// `tracks`, the tracks of the same pass (as trackFaults without members) are stored there. With
// a selection, rows of its frames (and of the frames before, as far as the seeds need them).
FaultMetricsSeries trackedMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        const VisibleMaskFn& visibleMask,
                                        std::span<const Fault> faults,
                                        const CandidateOptions& options = {},
                                        const MetricsOptions& metrics = {},
                                        std::vector<FaultTrack>* tracks = nullptr,
                                        const FrameSelection& selection = {});
// The same with each frame's candidates from `candidates`.
FaultMetricsSeries trackedMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        const CandidatesFn& candidates,
                                        std::span<const Fault> faults,
                                        const MetricsOptions& metrics = {},
                                        std::vector<FaultTrack>* tracks = nullptr,
                                        const FrameSelection& selection = {});

// What happened to tracked faults between two frames, read from their tracks: a fault first
// matched a candidate (appeared), faults matched to different candidates in the frame before
// share one now (linked), or faults that shared one now match different ones (split). Whether
// two faults share a candidate changes only once the new relation holds for kSettleFrames
// frames in a row: a link or split undone within fewer frames is flicker, no event (issue 41:
// at low thresholds faults linked and split every other frame or two), and one in the last
// kSettleFrames - 1 frames is not settled yet (no event).
inline constexpr std::size_t kSettleFrames = 3;
enum class FaultEventKind { Appeared, Linked, Split };
std::string_view faultEventKindName(FaultEventKind kind); // appeared | linked | split

struct FaultEvent {
    std::size_t frame = 0;
    FaultEventKind kind = FaultEventKind::Appeared;
    std::vector<std::size_t> faults; // indices into the faults tracked, ascending
    bool operator==(const FaultEvent&) const = default;
};

// Events in frame order; within a frame appeared, then linked, then split, each by its first
// fault. `tracks` as trackFaults gives them (one per fault, every frame).
std::vector<FaultEvent> faultEvents(std::span<const FaultTrack> tracks);

// The events of the selected frames, tracking only the frames they need: each selected frame,
// the frame before it and the kSettleFrames - 1 after, earlier frames back to a settled
// relation of every pair, and as far as needed to know whether a fault appeared before. Equal
// to the unselected run's events in those frames.
std::vector<FaultEvent> trackedFaultEvents(std::size_t frameCount, const FrameLoader& load,
                                           const VisibleMaskFn& visibleMask,
                                           std::span<const Fault> faults,
                                           const CandidateOptions& options = {},
                                           const FrameSelection& selection = {});

} // namespace faultline::core
