// Planted planar faults on a cubic lattice: every planted fault is found as one candidate with
// precision and recall above 95%, orientation within 2 degrees, and the planted throw.
#include "core/faults/candidates.hpp"
#include "core/faults/metrics.hpp"
#include "core/faults/tracking.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

using namespace faultline::core;
using namespace faultline::core::testing;

namespace {

struct Score {
    double precision, recall;
};
Score score(const std::vector<std::int64_t>& found, const std::vector<std::int64_t>& planted) {
    std::vector<std::int64_t> common;
    std::set_intersection(found.begin(), found.end(), planted.begin(), planted.end(),
                          std::back_inserter(common));
    return {double(common.size()) / double(found.size()),
            double(common.size()) / double(planted.size())};
}

void expectOrientation(const FaultFrameMetrics& m, double dip, double dipDirection) {
    ASSERT_TRUE(m.planeValid);
    EXPECT_NEAR(m.dip, dip, 2.0);
    // Near vertical the dip direction is only defined up to 180 degrees.
    const double period = dip >= 88 ? 180.0 : 360.0;
    EXPECT_LT(angleDiff(m.dipDirection, dipDirection, period), 2.0)
        << "measured " << m.dipDirection << " planted " << dipDirection;
    const Vec3d n = normalFromOrientation(dip, dipDirection);
    const double angle =
        std::acos(std::min(1.0, std::fabs(dot3(n, m.normal)))) * 180 / std::numbers::pi;
    EXPECT_LT(angle, 2.0);
}

struct Orientation {
    double dip, dipDirection;
};

class PlantedFaultOrientation : public ::testing::TestWithParam<Orientation> {};

} // namespace

TEST_P(PlantedFaultOrientation, IsFoundWithItsDipDipDirectionAndThrow) {
    const Orientation o = GetParam();
    PlantedFault f;
    f.dip = o.dip;
    f.dipDirection = o.dipDirection;
    f.point = {16.23, 15.41, 12.17};
    f.halfWidth = 2.0;
    f.slip = 0.6;
    const PlantedModel model = plantFaults(34, 32, 26, {f});
    const CandidateSet set = findCandidates(model.frame, model.visible, {1.1, 50});
    ASSERT_EQ(set.candidates.size(), 1u);
    const Score s = score(set.candidates[0].ids, model.members[0]);
    EXPECT_GT(s.precision, 0.95);
    EXPECT_GT(s.recall, 0.95);

    const std::vector<Fault> faults = faultsFromCandidates(set.candidates, "C");
    const FaultFrameMetrics m = computeFrameMetrics(model.frame, 0, faults).at(0);
    expectOrientation(m, o.dip, o.dipDirection);
    EXPECT_NEAR(m.thickness, 4.0, 0.4); // slab 2 x halfWidth
    // Area: members / (lattice density 1 x slab width 4), plus a rim of cells at the edges.
    const double area = double(model.members[0].size()) / 4.0;
    EXPECT_GT(m.area, 0.9 * area);
    EXPECT_LT(m.area, 1.25 * area);
    ASSERT_EQ(m.throwStatus, ThrowStatus::Ok);
    EXPECT_GT(m.hangingWallSamples, 100u);
    EXPECT_GT(m.footwallSamples, 100u);
    EXPECT_NEAR(m.netSlip, 0.6, 0.03);
    if (o.dip < 88) { // sides are known: a normal fault, the hanging wall went down
        EXPECT_NEAR(m.throwVertical, -0.6 * std::sin(o.dip * std::numbers::pi / 180), 0.03);
        EXPECT_NEAR(m.dipSlip, 0.6, 0.03);
    } else {
        EXPECT_NEAR(std::fabs(m.throwVertical), 0.6 * std::sin(o.dip * std::numbers::pi / 180),
                    0.03);
    }
    EXPECT_NEAR(m.strikeSlip, 0.0, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Orientations, PlantedFaultOrientation,
                         ::testing::Values(Orientation{30, 0}, Orientation{45, 359},
                                           Orientation{60, 90}, Orientation{20, 200},
                                           Orientation{75, 271}, Orientation{50, 358.5},
                                           Orientation{85, 1.5}, Orientation{90, 135},
                                           Orientation{89.5, 0.5}, Orientation{12, 137}));

TEST(PlantedFaults, ThreeFaultsAreThreeCandidates) {
    // Three zones in blocks separated by gaps of two lattice spacings, plus scattered noise.
    std::vector<PlantedFault> faults(3);
    const Orientation o[3] = {{35, 10}, {70, 250}, {55, 355}};
    for (int k = 0; k < 3; ++k) {
        faults[k].dip = o[k].dip;
        faults[k].dipDirection = o[k].dipDirection;
        faults[k].boxMin = {k * 21.0, 0, 0};
        faults[k].boxMax = {k * 21.0 + 18, 39, 29};
        faults[k].point = {k * 21.0 + 9.3, 19.6, 14.2};
    }
    const PlantedModel model = plantFaults(61, 40, 30, faults);
    const CandidateSet set = findCandidates(model.frame, model.visible, {1.1, 50});
    ASSERT_EQ(set.candidates.size(), 3u);
    const std::vector<Fault> found = faultsFromCandidates(set.candidates, "C");
    std::vector<Fault> planted(3);
    for (int k = 0; k < 3; ++k)
        planted[k].ids = model.members[k];
    const auto matches = matchFaults(model.frame, set, planted);
    const auto metrics = computeFrameMetrics(model.frame, 0, found);
    std::vector<int> used;
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        ASSERT_GE(matches[k].candidate, 0);
        used.push_back(matches[k].candidate);
        EXPECT_GT(matches[k].precision, 0.95);
        EXPECT_GT(matches[k].recall, 0.95);
        const Score s = score(set.candidates[matches[k].candidate].ids, model.members[k]);
        EXPECT_DOUBLE_EQ(s.precision, matches[k].precision);
        expectOrientation(metrics[matches[k].candidate], o[k].dip, o[k].dipDirection);
        EXPECT_EQ(metrics[matches[k].candidate].throwStatus, ThrowStatus::NoDisplacement);
    }
    std::sort(used.begin(), used.end());
    EXPECT_EQ(used, (std::vector<int>{0, 1, 2}));
}
