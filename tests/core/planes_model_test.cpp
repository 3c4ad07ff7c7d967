#include "core/data/dataset.hpp"
#include "core/synth/planes_model.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

using namespace faultline::core;

namespace {

PlanesModelOptions tiny() {
    PlanesModelOptions o;
    o.columns = 20;
    o.layers = 16;
    o.rows = 14;
    o.frames = 5;
    o.faultCount = 2;
    o.seed = 3;
    return o;
}

// Members linked by centre distance <= 2.2 form one piece.
bool isConnected(const Frame& frame, const std::vector<std::int64_t>& ids) {
    if (ids.empty())
        return true;
    std::vector<char> seen(ids.size(), 0);
    std::vector<std::size_t> stack = {0};
    seen[0] = 1;
    std::size_t reached = 1;
    auto at = [&](std::size_t k) { return *frame.rowOf(ids[k]); };
    while (!stack.empty()) {
        const std::size_t k = stack.back();
        stack.pop_back();
        const std::size_t a = at(k);
        for (std::size_t m = 0; m < ids.size(); ++m) {
            if (seen[m])
                continue;
            const std::size_t b = at(m);
            const double dx = frame.x[a] - frame.x[b], dy = frame.y[a] - frame.y[b],
                         dz = frame.z[a] - frame.z[b];
            if (dx * dx + dy * dy + dz * dz <= 2.2 * 2.2) {
                seen[m] = 1;
                ++reached;
                stack.push_back(m);
            }
        }
    }
    return reached == ids.size();
}

} // namespace

TEST(PlanesModel, NormalFollowsTheOrientationContract) {
    auto n = planeNormal(90, 90); // vertical plane striking north, dipping east
    EXPECT_NEAR(n[0], 1, 1e-12);
    EXPECT_NEAR(n[1], 0, 1e-12);
    EXPECT_NEAR(n[2], 0, 1e-12);
    n = planeNormal(0, 123); // horizontal
    EXPECT_NEAR(n[2], 1, 1e-12);
    n = planeNormal(60, 180); // dips south: upward normal leans south
    EXPECT_NEAR(n[0], 0, 1e-12);
    EXPECT_NEAR(n[1], -std::sin(60 * M_PI / 180), 1e-12);
    EXPECT_NEAR(n[2], 0.5, 1e-12);
}

TEST(PlanesModel, GivenVerticalFaultHasExactlyTheSpheresNearItsPlane) {
    PlanesModelOptions o = tiny();
    PlaneFaultSpec s;
    s.centre = {20.5, 15, 12};
    s.dip = 90;
    s.dipDirection = 90; // the plane x = 20.5
    s.throwLength = 0;
    s.radius = 1000; // the whole block
    o.faults = {s};
    o.halfThickness = 1.6; // away from the lattice's half-integer distances
    const PlanesModel m = generatePlanesModel(o);
    ASSERT_EQ(m.faults.size(), 1u);
    const auto& f = m.faults[0];
    EXPECT_NEAR(f.strike, 0, 1e-12);
    // The last frame: exactly the spheres with |x0 - 20.5| <= 1.6, i.e. x0 in {19, 20, 21, 22}.
    const Frame& frame = m.frames.back();
    std::vector<std::int64_t> want;
    for (std::size_t i = 0; i < frame.size(); ++i) {
        const double x0 = frame.attribute("x0")->value(i);
        if (x0 >= 19 && x0 <= 22)
            want.push_back(frame.ids[i]);
    }
    ASSERT_FALSE(want.empty());
    EXPECT_EQ(f.members.front(), std::vector<std::int64_t>{});
    EXPECT_EQ(f.members.back(), want);
    EXPECT_EQ(f.firstFrame, 1);
}

TEST(PlanesModel, RandomFaultsGrowApartAndCarryTheDamage) {
    const PlanesModel m = generatePlanesModel(tiny());
    ASSERT_EQ(m.faults.size(), 2u);
    ASSERT_EQ(m.frames.size(), 5u);
    for (const auto& f : m.faults) {
        ASSERT_EQ(f.members.size(), 5u);
        EXPECT_TRUE(f.members.front().empty()) << f.name;
        EXPECT_FALSE(f.members.back().empty()) << f.name;
        EXPECT_GE(f.spec.dip, 45);
        EXPECT_LE(f.spec.dip, 75);
        for (std::size_t k = 1; k < f.members.size(); ++k) {
            EXPECT_TRUE(std::includes(f.members[k].begin(), f.members[k].end(),
                                      f.members[k - 1].begin(), f.members[k - 1].end()))
                << f.name << " lost members at frame " << k;
            EXPECT_TRUE(isConnected(m.frames[k], f.members[k])) << f.name << " frame " << k;
        }
    }
    // No sphere in two faults; members damaged, every other sphere intact.
    const Frame& last = m.frames.back();
    std::vector<int> owner(last.size(), -1);
    for (int k = 0; k < 2; ++k)
        for (auto id : m.faults[k].members.back()) {
            const auto row = *last.rowOf(id);
            EXPECT_EQ(owner[row], -1);
            owner[row] = k;
        }
    for (std::size_t i = 0; i < last.size(); ++i) {
        const double broken = last.attribute("broken_bonds")->value(i);
        const double strain = last.attribute("strain")->value(i);
        if (owner[i] >= 0) {
            EXPECT_GE(broken, 3);
            EXPECT_GE(strain, 0.15);
        } else {
            EXPECT_EQ(broken, 0);
            EXPECT_LE(strain, 0.02);
        }
    }
}

TEST(PlanesModel, SameSeedSameModelAndTruthReadsBack) {
    const PlanesModel a = generatePlanesModel(tiny());
    const PlanesModel b = generatePlanesModel(tiny());
    EXPECT_EQ(planesTruthJson(a), planesTruthJson(b));
    const auto dir =
        std::filesystem::temp_directory_path() /
        ("faultline_planes_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    const auto files = writePlanesModel(a, dir.string(), true);
    auto ds = Dataset::open({files.dump});
    ASSERT_EQ(ds->frameCount(), 5u);
    EXPECT_EQ(ds->frame(4)->x, a.frames[4].x);
    EXPECT_EQ(ds->frame(4)->attribute("broken_bonds")->ints,
              a.frames[4].attribute("broken_bonds")->ints);
    std::ifstream in(files.truth);
    const auto j = nlohmann::json::parse(in);
    ASSERT_EQ(j["faults"].size(), 2u);
    EXPECT_EQ(j["faults"][0]["name"], "F1");
    EXPECT_DOUBLE_EQ(j["faults"][0]["dip"].get<double>(), a.faults[0].spec.dip);
    EXPECT_EQ(j["faults"][1]["members"][4].get<std::vector<std::int64_t>>(),
              a.faults[1].members[4]);
}

TEST(PlanesModel, TooManyFaultsForTheBlockIsAnError) {
    PlanesModelOptions o = tiny();
    o.faultCount = 40;
    EXPECT_THROW(generatePlanesModel(o), std::runtime_error);
    o.faultCount = 1;
    o.dip = 95;
    EXPECT_THROW(generatePlanesModel(o), std::invalid_argument);
}
