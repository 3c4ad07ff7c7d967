// Fault networks: faults that cross (X), end against each other (V, T), and curve (listric) come
// out as one candidate each, with their members and orientation, and noise is left out.
#include "core/faults/candidates.hpp"
#include "core/faults/fault_export.hpp"
#include "core/faults/metrics.hpp"
#include "core/faults/tracking.hpp"
#include "core/selection/visibility.hpp"
#include "core/synth/planes_model.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

using namespace faultline::core;
using namespace faultline::core::testing;

namespace {

std::vector<std::int64_t> without(const std::vector<std::int64_t>& ids,
                                  const std::vector<std::int64_t>& excluded) {
    std::vector<std::int64_t> out;
    std::set_difference(ids.begin(), ids.end(), excluded.begin(), excluded.end(),
                        std::back_inserter(out));
    return out;
}

std::size_t sharedCount(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
    std::vector<std::int64_t> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    return common.size();
}

// Each planted fault (ids shared by two zones left out) against the candidate holding most
// of it: that candidate's precision and recall, and the candidate's index.
struct Found {
    int candidate = -1;
    double precision = 0, recall = 0;
};

Found bestMatch(const CandidateSet& set, const std::vector<std::int64_t>& planted,
                const std::vector<std::int64_t>& excluded) {
    const auto truth = without(planted, excluded);
    Found f;
    std::size_t best = 0;
    for (std::size_t c = 0; c < set.candidates.size(); ++c)
        if (const std::size_t k = sharedCount(truth, set.candidates[c].ids); k > best) {
            best = k;
            f.candidate = int(c);
        }
    if (f.candidate >= 0) {
        const auto found = without(set.candidates[std::size_t(f.candidate)].ids, excluded);
        f.precision = double(best) / double(found.size());
        f.recall = double(best) / double(truth.size());
    }
    return f;
}

double normalAngle(const Vec3d& measured, double dip, double dipDirection) {
    const Vec3d n = normalFromOrientation(dip, dipDirection);
    return std::acos(std::min(1.0, std::fabs(dot3(n, measured)))) * 180 / std::numbers::pi;
}

} // namespace

TEST(FaultNetwork, PlantedNetworkGivesEachFaultItsOwnCandidate) {
    const PlanesModel model = generatePlanesModel(planesNetworkOptions());
    const Frame& last = model.frames.back();
    ASSERT_GT(last.size(), 150000u);
    ASSERT_FALSE(model.shared.empty());
    ASSERT_FALSE(model.noise.empty());
    const std::vector<VariableThreshold> broken{{"broken_bonds", 3, 1e30, true}};
    const VisibilityResult visible = computeVisibility(last, {}, broken);

    CandidateOptions options;
    options.minSize = 50;
    const CandidateSet set = findCandidates(last, visible.mask, options);
    ASSERT_EQ(set.candidates.size(), model.faults.size());
    const std::vector<Fault> faults = faultsFromCandidates(set.candidates, "C");
    const auto metrics = computeFrameMetrics(last, model.frames.size() - 1, faults);
    std::vector<int> used;
    for (const PlaneFault& planted : model.faults) {
        SCOPED_TRACE(planted.name);
        const Found f = bestMatch(set, planted.members.back(), model.shared);
        ASSERT_GE(f.candidate, 0);
        used.push_back(f.candidate);
        EXPECT_GE(f.precision, 0.95);
        EXPECT_GE(f.recall, 0.95);
        if (planted.spec.listricDip)
            continue; // one curved fault: no single plane to compare
        const FaultFrameMetrics& m = metrics[std::size_t(f.candidate)];
        ASSERT_TRUE(m.planeValid);
        EXPECT_NEAR(m.dip, planted.spec.dip, 3.0);
        EXPECT_LT(angleDiff(m.dipDirection, planted.spec.dipDirection), 3.0);
        EXPECT_LT(normalAngle(m.normal, planted.spec.dip, planted.spec.dipDirection), 3.0);
    }
    std::sort(used.begin(), used.end());
    EXPECT_EQ(std::unique(used.begin(), used.end()), used.end()) << "two faults in one candidate";
    // Noise joins no fault unless it touches one.
    std::size_t noiseInFaults = 0;
    for (const auto& c : set.candidates)
        noiseInFaults += sharedCount(c.ids, model.noise);
    EXPECT_LT(noiseInFaults, model.noise.size() / 4);
}

TEST(FaultNetwork, ConnectedMethodStillJoinsTouchingFaults) {
    const PlanesModel model = generatePlanesModel(planesNetworkOptions());
    const Frame& last = model.frames.back();
    const std::vector<VariableThreshold> broken{{"broken_bonds", 3, 1e30, true}};
    const VisibilityResult visible = computeVisibility(last, {}, broken);
    CandidateOptions options;
    options.method = CandidateMethod::Connected;
    options.minSize = 50;
    const CandidateSet set = findCandidates(last, visible.mask, options);
    // F3 and F4 meet in a V: linking by distance makes them one candidate.
    const Found f3 = bestMatch(set, model.faults[2].members.back(), model.shared);
    const Found f4 = bestMatch(set, model.faults[3].members.back(), model.shared);
    EXPECT_EQ(f3.candidate, f4.candidate);
    EXPECT_GE(f3.recall, 0.95);
    EXPECT_GE(f4.recall, 0.95);
}

TEST(FaultNetwork, ConjugateCrossingOnACubicLatticeIsTwoFaults) {
    PlantedFault a, b;
    a.dip = 60, a.dipDirection = 90, a.point = {20.3, 15.2, 14.6}, a.halfWidth = 1.5;
    b.dip = 60, b.dipDirection = 270, b.point = a.point, b.halfWidth = 1.5;
    const PlantedModel model = plantFaults(41, 30, 30, {a, b});
    std::vector<std::int64_t> shared;
    std::set_intersection(model.members[0].begin(), model.members[0].end(),
                          model.members[1].begin(), model.members[1].end(),
                          std::back_inserter(shared));
    CandidateOptions options;
    options.minSize = 50;
    const CandidateSet set = findCandidates(model.frame, model.visible, options);
    ASSERT_EQ(set.candidates.size(), 2u);
    for (int k = 0; k < 2; ++k) {
        SCOPED_TRACE(k);
        const Found f = bestMatch(set, model.members[std::size_t(k)], shared);
        EXPECT_GE(f.precision, 0.95);
        EXPECT_GE(f.recall, 0.95);
    }
    EXPECT_NE(bestMatch(set, model.members[0], shared).candidate,
              bestMatch(set, model.members[1], shared).candidate);
}

// A T: a steep fault (north-striking, dipping 80 degrees east) whose zone stops at a gently
// dipping one (30 degrees north), both 3 wide, the branch clipped to `boxMin`..`boxMax`. The
// two come out as two candidates, each matching its planted fault to `atLeast` (precision and
// recall).
void expectTheBranchApart(const Vec3d& boxMin, const Vec3d& boxMax, std::size_t smallerBy,
                          double atLeast) {
    PlantedFault main, branch;
    main.dip = 30, main.dipDirection = 0, main.point = {20.4, 15.3, 10.2}, main.halfWidth = 1.5;
    branch.dip = 80, branch.dipDirection = 90, branch.point = {20.4, 15.3, 20.1};
    branch.halfWidth = 1.5;
    branch.boxMin = boxMin;
    branch.boxMax = boxMax;
    const PlantedModel model = plantFaults(41, 31, 30, {main, branch});
    ASSERT_GT(model.members[0].size(), smallerBy * model.members[1].size());
    CandidateOptions options;
    options.minSize = 50;
    const CandidateSet set = findCandidates(model.frame, model.visible, options);
    ASSERT_EQ(set.candidates.size(), 2u);
    const Found m = bestMatch(set, model.members[0], {});
    const Found b = bestMatch(set, model.members[1], {});
    EXPECT_NE(m.candidate, b.candidate);
    EXPECT_GE(m.precision, atLeast);
    EXPECT_GE(m.recall, atLeast);
    EXPECT_GE(b.precision, atLeast);
    EXPECT_GE(b.recall, atLeast);
}

// The main plane's highest point within the block's y range (its south edge).
const double kMainTop = 10.2 + std::tan(30 * std::numbers::pi / 180) * 15.3;

TEST(FaultNetwork, FaultEndingAgainstAnotherIsItsOwnFault) {
    // The branch only above the main fault: clipped at the main plane's highest point.
    expectTheBranchApart({-1e9, -1e9, kMainTop + 1.0}, {1e9, 1e9, 1e9}, 1, 0.95);
}

// Step 8 joins the touching segments of one thin sheet: a small fault ending against a large
// one is no segment of it, however flat the large one makes the two together (without the test
// of each part's own spread across the joint plane, kSegmentShare, step 8 joined them here).
TEST(FaultNetwork, ASmallFaultEndingAgainstALargeOneIsItsOwnFault) {
    // Over ten rows above the main fault's south edge, ending against its upper side.
    expectTheBranchApart({-1e9, -1e9, kMainTop}, {1e9, 10.0, kMainTop + 10.0}, 8, 0.9);
}

TEST(FaultNetwork, ListricFaultIsOneCandidate) {
    PlanesModelOptions o;
    o.columns = 60, o.layers = 30, o.rows = 40, o.frames = 2;
    PlaneFaultSpec f;
    f.dip = 70, f.dipDirection = 90, f.centre = {50, 25, 36}, f.radius = 45, f.throwLength = 2;
    f.listricDip = 30;
    o.faults = {f};
    const PlanesModel model = generatePlanesModel(o);
    const Frame& last = model.frames.back();
    const std::vector<VariableThreshold> broken{{"broken_bonds", 3, 1e30, true}};
    const VisibilityResult visible = computeVisibility(last, {}, broken);
    CandidateOptions options;
    options.minSize = 50;
    const CandidateSet set = findCandidates(last, visible.mask, options);
    ASSERT_EQ(set.candidates.size(), 1u);
    const Found found = bestMatch(set, model.faults[0].members.back(), {});
    EXPECT_GE(found.precision, 0.95);
    EXPECT_GE(found.recall, 0.95);
}

TEST(FaultNetwork, ResultDoesNotDependOnRowOrderOrThreads) {
    PlantedFault a, b;
    a.dip = 55, a.dipDirection = 45, a.point = {15.5, 15.5, 12.5};
    b.dip = 55, b.dipDirection = 225, b.point = a.point;
    const PlantedModel one = plantFaults(31, 31, 25, {a, b}, 3, 7);
    const PlantedModel two = plantFaults(31, 31, 25, {a, b}, 3, 11); // other row order, noise
    CandidateOptions options;
    options.minSize = 30;
    const CandidateSet s1 = findCandidates(one.frame, one.visible, options);
    const CandidateSet s1again = findCandidates(one.frame, one.visible, options);
    ASSERT_EQ(s1.candidates.size(), s1again.candidates.size());
    for (std::size_t c = 0; c < s1.candidates.size(); ++c)
        EXPECT_EQ(s1.candidates[c].ids, s1again.candidates[c].ids);
    const CandidateSet s2 = findCandidates(two.frame, two.visible, options);
    EXPECT_EQ(s1.candidates.size(), s2.candidates.size());
}

TEST(FaultNetwork, BadOptionsAreRejected) {
    const Frame f = frameOf({{1, 0, 0, 0}});
    const std::vector<std::uint8_t> vis{1};
    CandidateOptions o;
    o.angle = 0;
    EXPECT_THROW(findCandidates(f, vis, o), std::invalid_argument);
    o.angle = 90;
    EXPECT_THROW(findCandidates(f, vis, o), std::invalid_argument);
    o.angle = 20;
    o.radius = -1;
    EXPECT_THROW(findCandidates(f, vis, o), std::invalid_argument);
    o.radius = NAN;
    EXPECT_THROW(findCandidates(f, vis, o), std::invalid_argument);
    EXPECT_EQ(parseCandidateMethod("connected"), CandidateMethod::Connected);
    EXPECT_THROW(parseCandidateMethod("graph"), std::invalid_argument);
}

TEST(FaultNetwork, SegmentsThatGrowIntoEachOtherLinkInTheEvents) {
    // Two coplanar segments along strike, growing until their tips overlap: apart at first
    // (two candidates), one fault once they meet.
    PlanesModelOptions o;
    o.columns = 40, o.layers = 60, o.rows = 30, o.frames = 7;
    PlaneFaultSpec a;
    a.dip = 60, a.dipDirection = 90, a.centre = {40, 29, 26}, a.radius = 24, a.throwLength = 1;
    PlaneFaultSpec b = a;
    b.centre = {40, 69, 26};
    o.faults = {a, b};
    const PlanesModel model = generatePlanesModel(o);
    std::vector<Fault> faults(2);
    for (int k = 0; k < 2; ++k) {
        faults[std::size_t(k)].name = model.faults[std::size_t(k)].name;
        faults[std::size_t(k)].ids = model.faults[std::size_t(k)].members.back();
    }
    const std::vector<VariableThreshold> broken{{"broken_bonds", 3, 1e30, true}};
    CandidateOptions options;
    options.minSize = 20;
    const auto tracks = trackFaults(
        model.frames.size(),
        [&](std::size_t f) {
            return std::shared_ptr<const Frame>(&model.frames[f], [](const Frame*) {});
        },
        [&](const Frame& frame, std::size_t) { return computeVisibility(frame, {}, broken).mask; },
        faults, options);
    const auto events = faultEvents(tracks);
    ASSERT_GE(events.size(), 3u);
    EXPECT_EQ(events[0], (FaultEvent{1, FaultEventKind::Appeared, {0}}));
    EXPECT_EQ(events[1], (FaultEvent{1, FaultEventKind::Appeared, {1}}));
    std::size_t linkedAt = 0;
    for (const FaultEvent& e : events) {
        EXPECT_NE(e.kind, FaultEventKind::Split);
        if (e.kind == FaultEventKind::Linked) {
            EXPECT_EQ(e.faults, (std::vector<std::size_t>{0, 1}));
            linkedAt = e.frame;
        }
    }
    // Tips 16 apart at frame 3 (two neighbourhoods and more), 8 apart at frame 4, touching at 5:
    // coplanar segments join once their tips are within about two neighbourhood radii.
    EXPECT_GE(linkedAt, 4u);
    EXPECT_EQ(faultEventsCsv(faults, events).substr(0, 38),
              "frame,kind,faults\n1,appeared,F1\n1,appe");

    // Growth: F1 followed as its candidate lengthens along strike as the segment grows (4
    // radii a frame at each tip), and spans both segments once they link.
    const FaultMetricsSeries growth = trackedMetricsSeries(
        model.frames.size(),
        [&](std::size_t f) {
            return std::shared_ptr<const Frame>(&model.frames[f], [](const Frame*) {});
        },
        [&](const Frame& frame, std::size_t) { return computeVisibility(frame, {}, broken).mask; },
        faults, options);
    EXPECT_EQ(growth.at(0, 0).count, 0u);
    for (std::size_t f = 2; f < linkedAt; ++f) {
        SCOPED_TRACE(f);
        EXPECT_GT(growth.at(f, 0).length, growth.at(f - 1, 0).length + 4);
        EXPECT_NEAR(growth.at(f, 0).length, 2 * 24.0 * double(f) / 6, 4.0);
        EXPECT_GT(growth.at(f, 0).count, growth.at(f - 1, 0).count);
    }
    EXPECT_GT(growth.at(6, 0).length, 80.0);                 // both segments: 40 apart + 2 x 24
    EXPECT_EQ(growth.at(6, 0).count, growth.at(6, 1).count); // one candidate for both
}
