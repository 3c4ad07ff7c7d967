#include "core/faults/tracking.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <map>
#include <set>

namespace faultline::core {

std::vector<std::uint32_t> memberRows(const Frame& frame, std::span<const std::int64_t> ids) {
    std::vector<std::uint32_t> rows;
    rows.reserve(ids.size());
    for (std::int64_t id : ids)
        if (const auto row = frame.rowOf(id))
            rows.push_back(static_cast<std::uint32_t>(*row));
    return rows;
}

namespace {
CandidateMatch matchOne(const Frame& frame, const CandidateSet& set, const Fault& fault) {
    CandidateMatch m;
    std::vector<std::int32_t> labels;
    labels.reserve(fault.ids.size());
    for (std::int64_t id : fault.ids) {
        const auto row = frame.rowOf(id);
        if (!row)
            continue;
        ++m.present;
        if (const std::int32_t label = set.rowLabel[*row]; label >= 0)
            labels.push_back(label);
    }
    if (labels.empty())
        return m;
    std::sort(labels.begin(), labels.end());
    std::size_t best = 0;
    for (std::size_t i = 0; i < labels.size();) {
        std::size_t j = i;
        while (j < labels.size() && labels[j] == labels[i])
            ++j;
        if (j - i > best) { // strict: ties keep the lower (larger) candidate
            best = j - i;
            m.candidate = labels[i];
        }
        i = j;
    }
    m.shared = best;
    m.candidateSize = set.candidates[static_cast<std::size_t>(m.candidate)].size();
    m.jaccard = double(m.shared) / double(m.present + m.candidateSize - m.shared);
    m.precision = double(m.shared) / double(m.candidateSize);
    m.recall = double(m.shared) / double(m.present);
    return m;
}
} // namespace

std::vector<CandidateMatch> matchFaults(const Frame& frame, const CandidateSet& candidates,
                                        std::span<const Fault> faults) {
    assert(candidates.rowLabel.size() == frame.size());
    std::vector<CandidateMatch> matches(faults.size());
    tbb::parallel_for(std::size_t(0), faults.size(),
                      [&](std::size_t k) { matches[k] = matchOne(frame, candidates, faults[k]); });
    return matches;
}

std::vector<FaultTrack> trackFaults(std::size_t frameCount, const FrameLoader& load,
                                    const VisibleMaskFn& visibleMask, std::span<const Fault> faults,
                                    const CandidateOptions& options, bool keepMembers) {
    std::vector<FaultTrack> tracks(faults.size());
    for (auto& t : tracks)
        t.points.reserve(frameCount);
    for (std::size_t f = 0; f < frameCount; ++f) {
        const std::shared_ptr<const Frame> frame = load(f);
        const std::vector<std::uint8_t> mask = visibleMask(*frame, f);
        const CandidateSet set = findCandidates(*frame, mask, options);
        const std::vector<CandidateMatch> matches = matchFaults(*frame, set, faults);
        for (std::size_t k = 0; k < faults.size(); ++k) {
            FaultTrackPoint p;
            p.frame = f;
            p.match = matches[k];
            if (keepMembers && p.match.candidate >= 0)
                p.members = set.candidates[static_cast<std::size_t>(p.match.candidate)].ids;
            tracks[k].points.push_back(std::move(p));
        }
    }
    return tracks;
}

FaultMetricsSeries trackedMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        const VisibleMaskFn& visibleMask,
                                        std::span<const Fault> faults,
                                        const CandidateOptions& options,
                                        const MetricsOptions& metrics,
                                        std::vector<FaultTrack>* tracks) {
    FaultMetricsSeries series;
    if (tracks)
        tracks->assign(faults.size(), FaultTrack{});
    series.frameCount = frameCount;
    series.faultCount = faults.size();
    series.rows.reserve(frameCount * faults.size());
    std::vector<Fault> now(faults.begin(), faults.end());
    for (std::size_t f = 0; f < frameCount; ++f) {
        const std::shared_ptr<const Frame> frame = load(f);
        const CandidateSet set = findCandidates(*frame, visibleMask(*frame, f), options);
        const std::vector<CandidateMatch> matches = matchFaults(*frame, set, faults);
        for (std::size_t k = 0; k < faults.size(); ++k) {
            if (tracks)
                (*tracks)[k].points.push_back({f, matches[k], {}});
            now[k].ids = matches[k].candidate >= 0
                             ? set.candidates[static_cast<std::size_t>(matches[k].candidate)].ids
                             : std::vector<std::int64_t>{};
        }
        auto rows = computeFrameMetrics(*frame, f, now, metrics);
        series.rows.insert(series.rows.end(), std::make_move_iterator(rows.begin()),
                           std::make_move_iterator(rows.end()));
    }
    series.seeds = seedsFromRows(series.rows, faults.size());
    return series;
}

std::string_view faultEventKindName(FaultEventKind kind) {
    switch (kind) {
    case FaultEventKind::Appeared:
        return "appeared";
    case FaultEventKind::Linked:
        return "linked";
    case FaultEventKind::Split:
        return "split";
    }
    return "appeared";
}

std::vector<FaultEvent> faultEvents(std::span<const FaultTrack> tracks) {
    std::vector<FaultEvent> events;
    std::size_t frames = 0;
    for (const FaultTrack& t : tracks)
        frames = std::max(frames, t.points.size());
    auto candidateAt = [&](std::size_t fault, std::size_t frame) -> std::int32_t {
        const auto& points = tracks[fault].points;
        return frame < points.size() ? points[frame].match.candidate : -1;
    };
    // Faults grouped by the candidate they match in a frame (candidate -> faults, ascending).
    auto groups = [&](std::size_t frame) {
        std::map<std::int32_t, std::vector<std::size_t>> byCandidate;
        for (std::size_t k = 0; k < tracks.size(); ++k)
            if (const std::int32_t c = candidateAt(k, frame); c >= 0)
                byCandidate[c].push_back(k);
        return byCandidate;
    };
    std::vector<std::uint8_t> seen(tracks.size(), 0);
    std::map<std::int32_t, std::vector<std::size_t>> before;
    for (std::size_t f = 0; f < frames; ++f) {
        const auto now = groups(f);
        for (std::size_t k = 0; k < tracks.size(); ++k)
            if (!seen[k] && candidateAt(k, f) >= 0) {
                seen[k] = 1;
                events.push_back({f, FaultEventKind::Appeared, {k}});
            }
        if (f > 0) {
            // Groups of one frame whose faults match two or more candidates in the other.
            auto parted = [&](const auto& groupsIn, std::size_t other, FaultEventKind kind) {
                std::vector<FaultEvent> found;
                for (const auto& [c, members] : groupsIn) {
                    std::set<std::int32_t> there;
                    for (std::size_t k : members)
                        if (const std::int32_t e = candidateAt(k, other); e >= 0)
                            there.insert(e);
                    if (members.size() >= 2 && there.size() >= 2)
                        found.push_back({f, kind, members});
                }
                std::sort(found.begin(), found.end(), [](const FaultEvent& a, const FaultEvent& b) {
                    return a.faults < b.faults;
                });
                events.insert(events.end(), found.begin(), found.end());
            };
            parted(now, f - 1, FaultEventKind::Linked);
            parted(before, f, FaultEventKind::Split);
        }
        before = now;
    }
    return events;
}

} // namespace faultline::core
