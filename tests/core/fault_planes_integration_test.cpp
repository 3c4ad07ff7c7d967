// Fault finding against the known-faults generator (issue 9): every planted fault is found as
// one candidate, its dip and dip direction within 2 degrees, members with precision and recall
// above 95%.
#include "core/faults/candidates.hpp"
#include "core/faults/metrics.hpp"
#include "core/selection/visibility.hpp"
#include "core/synth/planes_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

using namespace faultline::core;

namespace {
double angleGap(double a, double b) {
    const double d = std::fmod(std::fabs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}
} // namespace

class PlantedFaults : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(PlantedFaults, AreFoundWithTheirOrientationAndMembers) {
    PlanesModelOptions options = planesOptionsFor(ModelSize::Medium);
    options.seed = GetParam();
    options.faultCount = 3;
    options.frames = 4;
    const PlanesModel model = generatePlanesModel(options);
    const Frame& last = model.frames.back();

    // What a user does: show the spheres with broken bonds, ask for candidates.
    const std::vector<VariableThreshold> broken{{"broken_bonds", 1, 1e30, true}};
    const VisibilityResult visible = computeVisibility(last, {}, broken);
    CandidateOptions candidateOptions;
    candidateOptions.minSize = 20;
    const CandidateSet set = findCandidates(last, visible.mask, candidateOptions);
    ASSERT_EQ(set.candidates.size(), model.faults.size()) << "seed " << GetParam();

    for (const PlaneFault& planted : model.faults) {
        const auto& truth = planted.members.back();
        std::size_t best = 0, bestShared = 0;
        for (std::size_t c = 0; c < set.candidates.size(); ++c) {
            std::vector<std::int64_t> shared;
            std::set_intersection(truth.begin(), truth.end(), set.candidates[c].ids.begin(),
                                  set.candidates[c].ids.end(), std::back_inserter(shared));
            if (shared.size() > bestShared) {
                bestShared = shared.size();
                best = c;
            }
        }
        const auto& found = set.candidates[best].ids;
        const double precision = double(bestShared) / double(found.size());
        const double recall = double(bestShared) / double(truth.size());
        EXPECT_GT(precision, 0.95) << planted.name;
        EXPECT_GT(recall, 0.95) << planted.name;

        Fault fault;
        fault.name = planted.name;
        fault.ids = found;
        const auto metrics =
            computeFrameMetrics(last, model.frames.size() - 1, std::vector<Fault>{fault});
        ASSERT_EQ(metrics.size(), 1u);
        EXPECT_LT(std::fabs(metrics[0].dip - planted.spec.dip), 2.0)
            << planted.name << " dip " << planted.spec.dip << " dir " << planted.spec.dipDirection
            << " members " << truth.size();
        if (planted.spec.dip < 88) { // a vertical plane's dip direction is either side
            EXPECT_LT(angleGap(metrics[0].dipDirection, planted.spec.dipDirection), 2.0)
                << planted.name;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, PlantedFaults, ::testing::Range<std::uint64_t>(1, 13));
