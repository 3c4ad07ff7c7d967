#include "core/faults/tracking.hpp"
#include "core/util/enum_names.hpp"
#include "core/util/union_find.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <limits>
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
                                    const CandidateOptions& options, bool keepMembers,
                                    const FrameSelection& selection) {
    std::vector<FaultTrack> tracks(faults.size());
    const std::vector<std::size_t> frames = selection.frames(frameCount);
    for (auto& t : tracks)
        t.points.reserve(frames.size());
    for (const std::size_t f : frames) {
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

CandidatesFn candidatesOfVisible(const VisibleMaskFn& visibleMask,
                                 const CandidateOptions& options) {
    return [visibleMask, options](const Frame& frame, std::size_t f) {
        return std::make_shared<const CandidateSet>(
            findCandidates(frame, visibleMask(frame, f), options));
    };
}

FaultMetricsSeries
trackedMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                     const VisibleMaskFn& visibleMask, std::span<const Fault> faults,
                     const CandidateOptions& options, const MetricsOptions& metrics,
                     std::vector<FaultTrack>* tracks, const FrameSelection& selection) {
    return trackedMetricsSeries(frameCount, load, candidatesOfVisible(visibleMask, options), faults,
                                metrics, tracks, selection);
}

FaultMetricsSeries trackedMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        const CandidatesFn& candidates,
                                        std::span<const Fault> faults,
                                        const MetricsOptions& metrics,
                                        std::vector<FaultTrack>* tracks,
                                        const FrameSelection& selection) {
    FaultMetricsSeries series;
    if (tracks)
        tracks->assign(faults.size(), FaultTrack{});
    series.frameCount = frameCount;
    series.faultCount = faults.size();
    series.selection = selection;
    series.rows.resize(frameCount * faults.size());
    for (std::size_t i = 0; i < series.rows.size(); ++i) {
        series.rows[i].frame = i / faults.size();
        series.rows[i].fault = i % faults.size();
    }
    MetricsOptions seedOnly = metrics;
    seedOnly.computeThrow = false;
    std::vector<Fault> now(faults.begin(), faults.end());
    std::vector<std::uint8_t> seeded(faults.size(), 0); // a break seen in an earlier frame
    for (std::size_t f = 0; f < frameCount; ++f) {
        const bool wanted = selection.contains(f);
        // Outside the selection a frame is read only while some fault has no seed yet.
        if (!wanted && std::all_of(seeded.begin(), seeded.end(), [](std::uint8_t s) { return s; }))
            continue;
        const std::shared_ptr<const Frame> frame = load(f);
        const std::shared_ptr<const CandidateSet> found = candidates(*frame, f);
        const CandidateSet& set = *found;
        const std::vector<CandidateMatch> matches = matchFaults(*frame, set, faults);
        for (std::size_t k = 0; k < faults.size(); ++k) {
            if (tracks && wanted)
                (*tracks)[k].points.push_back({f, matches[k], {}});
            now[k].ids = matches[k].candidate >= 0
                             ? set.candidates[static_cast<std::size_t>(matches[k].candidate)].ids
                             : std::vector<std::int64_t>{};
        }
        auto rows = computeFrameMetrics(*frame, f, now, wanted ? metrics : seedOnly);
        for (std::size_t k = 0; k < faults.size(); ++k)
            if (rows[k].broken > 0)
                seeded[k] = 1;
        std::move(rows.begin(), rows.end(),
                  series.rows.begin() + std::ptrdiff_t(f * faults.size()));
    }
    if (!faults.empty())
        series.seeds = seedsFromRows(series.rows, faults.size());
    return series;
}

namespace {
constexpr EnumName<FaultEventKind> kEventKinds[] = {{FaultEventKind::Appeared, "appeared"},
                                                    {FaultEventKind::Linked, "linked"},
                                                    {FaultEventKind::Split, "split"}};
} // namespace

std::string_view faultEventKindName(FaultEventKind kind) {
    return nameIn(kEventKinds, kind, "appeared");
}

namespace {
// Two tracked faults in a frame: 1 in one candidate, 0 in different ones, -1 when either
// matches none (or the frame was not tracked).
int pairRelation(std::span<const FaultTrack> tracks, std::size_t frame, std::size_t i,
                 std::size_t j) {
    auto candidateAt = [&](std::size_t fault) -> std::int32_t {
        const auto& points = tracks[fault].points;
        return frame < points.size() ? points[frame].match.candidate : -1;
    };
    const std::int32_t a = candidateAt(i), b = candidateAt(j);
    return a < 0 || b < 0 ? -1 : int(a == b);
}
} // namespace

std::vector<FaultEvent> faultEvents(std::span<const FaultTrack> tracks) {
    std::vector<FaultEvent> events;
    std::size_t frames = 0;
    for (const FaultTrack& t : tracks)
        frames = std::max(frames, t.points.size());
    const std::size_t n = tracks.size();
    auto candidateAt = [&](std::size_t fault, std::size_t frame) -> std::int32_t {
        const auto& points = tracks[fault].points;
        return frame < points.size() ? points[frame].match.candidate : -1;
    };
    auto raw = [&](std::size_t f, std::size_t i, std::size_t j) {
        return pairRelation(tracks, f, i, j);
    };
    // Issue 41: at a low threshold two faults joined by a few spheres flicker, linked for a
    // frame or two and split again, over and over (46 events for 9 faults on the demo when only
    // one-frame flicker was read as such). A pair's relation changes only once the new one
    // holds for kSettleFrames frames in a row: the relation in a
    // frame is that of the latest such settled run starting at or before it, else the first
    // one seen. Frames where either fault matches nothing stay unknown (-1). A change in the
    // last kSettleFrames - 1 frames is not settled: the data ends before it could be.
    std::vector<std::vector<std::int8_t>> pair(n * n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            auto& out = pair[i * n + j];
            out.assign(frames, -1);
            int state = -1;
            for (std::size_t f = 0; f < frames; ++f) {
                const int r = raw(f, i, j);
                if (r < 0)
                    continue;
                if (state < 0) {
                    state = r;
                } else if (r != state) {
                    bool settled = f + kSettleFrames <= frames;
                    for (std::size_t g = f + 1; g < f + kSettleFrames && settled; ++g)
                        settled = raw(g, i, j) == r;
                    if (settled)
                        state = r;
                }
                out[f] = std::int8_t(state);
            }
        }
    auto together = [&](std::size_t f, std::size_t i, std::size_t j) -> int {
        return pair[std::min(i, j) * n + std::max(i, j)][f];
    };
    // Faults grouped in a frame: the components of "together" (a label per fault, -1 when it
    // matches nothing), so that groups are consistent: settling pairs one by one could leave
    // 1-4 and 4-7 together but 1-7 apart, read as a link and a split of one group at once.
    auto components = [&](std::size_t f) {
        UnionFind sets(n);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                if (together(f, i, j) == 1)
                    sets.unite(std::uint32_t(i), std::uint32_t(j));
        std::vector<std::int64_t> label(n, -1);
        for (std::size_t k = 0; k < n; ++k)
            if (candidateAt(k, f) >= 0)
                label[k] = sets.find(std::uint32_t(k));
        return label;
    };
    // The groups of two or more, each ascending, ordered by their first fault.
    auto groupsOf = [&](const std::vector<std::int64_t>& label) {
        std::map<std::int64_t, std::vector<std::size_t>> byRoot;
        for (std::size_t k = 0; k < n; ++k)
            if (label[k] >= 0)
                byRoot[label[k]].push_back(k);
        std::vector<std::vector<std::size_t>> out;
        for (auto& [root, members] : byRoot)
            if (members.size() >= 2)
                out.push_back(std::move(members));
        std::sort(out.begin(), out.end());
        return out;
    };
    std::vector<std::uint8_t> seen(n, 0);
    std::vector<std::int64_t> labelBefore;
    for (std::size_t f = 0; f < frames; ++f) {
        const std::vector<std::int64_t> label = components(f);
        for (std::size_t k = 0; k < n; ++k)
            if (!seen[k] && candidateAt(k, f) >= 0) {
                seen[k] = 1;
                events.push_back({f, FaultEventKind::Appeared, {k}});
            }
        if (f > 0) {
            // Groups of one frame with two faults in different groups in the other (both
            // matched there).
            auto parted = [&](const std::vector<std::int64_t>& in,
                              const std::vector<std::int64_t>& other, FaultEventKind kind) {
                for (const auto& members : groupsOf(in)) {
                    bool apart = false;
                    for (std::size_t a = 0; a < members.size() && !apart; ++a)
                        for (std::size_t b = a + 1; b < members.size() && !apart; ++b)
                            apart = other[members[a]] >= 0 && other[members[b]] >= 0 &&
                                    other[members[a]] != other[members[b]];
                    if (apart)
                        events.push_back({f, kind, members});
                }
            };
            parted(label, labelBefore, FaultEventKind::Linked);
            parted(labelBefore, label, FaultEventKind::Split);
        }
        labelBefore = label;
    }
    return events;
}

std::vector<FaultEvent> trackedFaultEvents(std::size_t frameCount, const FrameLoader& load,
                                           const VisibleMaskFn& visibleMask,
                                           std::span<const Fault> faults,
                                           const CandidateOptions& options,
                                           const FrameSelection& selection) {
    if (selection.everything())
        return faultEvents(trackFaults(frameCount, load, visibleMask, faults, options));
    const std::vector<std::size_t> frames = selection.frames(frameCount);
    if (frames.empty())
        return {};
    // A point per frame up to the last one a selected frame's relations are read from; frames
    // never tracked match nothing.
    const std::size_t end = std::min(frameCount, frames.back() + kSettleFrames);
    std::vector<FaultTrack> tracks(faults.size());
    for (auto& t : tracks) {
        t.points.resize(end);
        for (std::size_t f = 0; f < end; ++f)
            t.points[f].frame = f;
    }
    std::vector<std::uint8_t> tracked(end, 0);
    constexpr std::size_t kNever = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> firstSeen(faults.size(), kNever); // among tracked frames
    auto track = [&](std::size_t f) {
        if (tracked[f])
            return;
        tracked[f] = 1;
        const std::shared_ptr<const Frame> frame = load(f);
        const CandidateSet set = findCandidates(*frame, visibleMask(*frame, f), options);
        const std::vector<CandidateMatch> matches = matchFaults(*frame, set, faults);
        for (std::size_t k = 0; k < faults.size(); ++k) {
            tracks[k].points[f].match = matches[k];
            if (matches[k].candidate >= 0)
                firstSeen[k] = std::min(firstSeen[k], f);
        }
    };
    // Linked and split compare a frame with the one before. A pair's relation there is that of
    // the latest run of kSettleFrames equal relations starting at or before it (or the first
    // relation seen): frames f - 1 to f + kSettleFrames - 1, and earlier ones, kSettleFrames at
    // a time, until every pair has such a run starting before f - 1 (or frame 0 is reached).
    auto settledBefore = [&](std::size_t lo, std::size_t f) {
        // Whether each pair's relation has a settled run starting in [lo, f - 1]; and the
        // relation is known from lo on (lo = 0: from the first frame).
        if (lo == 0)
            return true;
        for (std::size_t i = 0; i < faults.size(); ++i)
            for (std::size_t j = i + 1; j < faults.size(); ++j) {
                bool found = false;
                for (std::size_t g = lo; g + 1 <= f && !found; ++g) {
                    auto rel = [&](std::size_t h) { return pairRelation(tracks, h, i, j); };
                    const int r = rel(g);
                    found = r >= 0 && g + kSettleFrames <= end;
                    for (std::size_t h = g + 1; h < g + kSettleFrames && found; ++h)
                        found = rel(h) == r;
                }
                if (!found)
                    return false;
            }
        return true;
    };
    for (const std::size_t f : frames) {
        std::size_t lo = f >= 1 ? f - 1 : 0;
        for (std::size_t g = lo; g < f + kSettleFrames && g < end; ++g)
            track(g);
        while (!settledBefore(lo, f)) {
            const std::size_t next = lo >= kSettleFrames ? lo - kSettleFrames : 0;
            for (std::size_t g = next; g < lo; ++g)
                track(g);
            lo = next;
        }
    }
    // "Appeared" needs every frame before a fault's first match.
    for (std::size_t f = 0; f < end; ++f)
        if (!tracked[f] &&
            std::any_of(firstSeen.begin(), firstSeen.end(), [f](std::size_t s) { return s > f; }))
            track(f);
    std::vector<FaultEvent> events = faultEvents(tracks);
    std::erase_if(events, [&](const FaultEvent& e) { return !selection.contains(e.frame); });
    return events;
}

} // namespace faultline::core
