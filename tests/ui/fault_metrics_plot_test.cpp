// Fault metrics over time: the cache's background job (computed once per set of members, kept
// through renames, dropped with the data) and the Faults panel's plot, whose clicks and drags
// go to frames like the timeline (previewed while held, one frame.set on release).
#include "panel_fixture.hpp"

#include "core/faults/metric_fields.hpp"
#include "ui/context/fault_metrics_cache.hpp"
#include "ui/dock/panel_ids.hpp"

#include <chrono>
#include <cmath>
#include <thread>

using namespace faultline;
using namespace faultline::test;
using core::Json;

namespace {

// Frame k: a flat 3 x 3 sheet of spheres (ids 1..9) at height z = k, so the centroid's height
// is the frame number.
core::Frame sheetAt(std::size_t k) {
    core::Frame f;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            f.ids.push_back(1 + i + 3 * j);
            f.x.push_back(float(i));
            f.y.push_back(float(j));
            f.z.push_back(float(k));
            f.radius.push_back(0.5f);
        }
    f.finalize();
    return f;
}

core::Fault faultOf(const std::string& name, std::vector<std::int64_t> ids) {
    core::Fault f;
    f.name = name;
    f.add(std::move(ids));
    return f;
}

} // namespace

TEST(FaultMetricsCache, ComputesInTheBackgroundOncePerMembership) {
    auto ds = core::Dataset::fromLoader(4, sheetAt);
    ui::JobRunner jobs;
    ui::FaultMetricsCache cache;
    core::Fault f = faultOf("F1", {1, 2, 3, 4, 5, 6, 7, 8, 9});
    const core::Fault* faults[] = {&f};
    cache.request(jobs, 0, ds, faults);
    EXPECT_TRUE(cache.computing());
    EXPECT_EQ(cache.find(ds, f), nullptr); // nothing until the job hands its result over
    jobs.waitAll();
    jobs.poll();
    EXPECT_FALSE(cache.computing());
    auto series = cache.find(ds, f);
    ASSERT_NE(series, nullptr);
    ASSERT_EQ(series->frames.size(), 4u);
    const core::MetricField* z = core::findMetricField("centroid_z");
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(series->frames[k].frame, k);
        EXPECT_EQ(series->frames[k].count, 9u);
        EXPECT_NEAR(z->value(series->frames[k]), double(k), 1e-9);
    }
    EXPECT_EQ(cache.lastFrameCount(), 4u);

    // A rename keeps the series; asking again starts nothing.
    core::Fault renamed = f;
    renamed.name = "north";
    const core::Fault* again[] = {&renamed};
    cache.request(jobs, 0, ds, again);
    EXPECT_FALSE(cache.computing());
    EXPECT_EQ(cache.find(ds, renamed), series);

    // New members: computed again; while that runs, a change of mind cancels it.
    core::Fault smaller = faultOf("F1", {1, 2, 3});
    const core::Fault* edited[] = {&smaller};
    cache.request(jobs, 0, ds, edited);
    EXPECT_TRUE(cache.computing());
    EXPECT_EQ(cache.find(ds, smaller), nullptr);
    jobs.waitAll();
    jobs.poll();
    ASSERT_NE(cache.find(ds, smaller), nullptr);
    EXPECT_EQ(cache.find(ds, smaller)->frames[0].count, 3u);

    // Other data: nothing is known about it.
    auto other = core::Dataset::fromLoader(2, sheetAt);
    EXPECT_EQ(cache.find(other, f), nullptr);
    cache.request(jobs, 0, other, faults);
    EXPECT_TRUE(cache.computing());
    jobs.waitAll();
    jobs.poll();
    ASSERT_NE(cache.find(other, f), nullptr);
    EXPECT_EQ(cache.find(other, f)->frames.size(), 2u);
    EXPECT_EQ(cache.find(ds, f), nullptr);
}

TEST(FaultMetricsCache, CancelledByTheUserIsNotStartedAgainUntilRetried) {
    auto ds = core::Dataset::fromLoader(20, [](std::size_t k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        return sheetAt(k);
    });
    ui::JobRunner jobs;
    ui::FaultMetricsCache cache;
    core::Fault f = faultOf("F1", {1, 2, 3, 4});
    const core::Fault* faults[] = {&f};
    cache.request(jobs, 0, ds, faults);
    ASSERT_EQ(jobs.running().size(), 1u);
    jobs.running()[0]->cancel(); // the status bar's Cancel
    jobs.waitAll();
    jobs.poll();
    cache.request(jobs, 0, ds, faults);
    EXPECT_FALSE(cache.computing());
    EXPECT_FALSE(jobs.busy());
    EXPECT_EQ(cache.lastError(), "cancelled");
    EXPECT_EQ(cache.find(ds, f), nullptr);
    cache.retry();
    cache.request(jobs, 0, ds, faults);
    EXPECT_TRUE(cache.computing());
    jobs.waitAll();
    jobs.poll();
    ASSERT_NE(cache.find(ds, f), nullptr);
    EXPECT_TRUE(cache.lastError().empty());
}

TEST(FaultMetricsCache, AFaultNoLongerShownIsNotWaitedFor) {
    // Frames that take a while to load: the job for the first fault is still running when the
    // user moves on to another fault, and is cancelled.
    auto ds = core::Dataset::fromLoader(50, [&](std::size_t k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return sheetAt(k);
    });
    ui::JobRunner jobs;
    ui::FaultMetricsCache cache;
    core::Fault a = faultOf("A", {1, 2, 3, 4, 5, 6}), b = faultOf("B", {4, 5, 6, 7, 8, 9});
    const core::Fault* first[] = {&a};
    const core::Fault* second[] = {&b};
    cache.request(jobs, 0, ds, first);
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    cache.request(jobs, 0, ds, second);
    EXPECT_TRUE(cache.computing());
    jobs.waitAll();
    jobs.poll();
    EXPECT_EQ(cache.find(ds, a), nullptr); // cancelled: its result is not kept
    ASSERT_NE(cache.find(ds, b), nullptr);
    EXPECT_EQ(cache.find(ds, b)->frames.size(), 50u);
}

// Fault F1: the column x = 1 of the 4 x 4 x 4 lattice (a vertical plane striking north),
// selected, with the Faults panel shown and its metrics computed.
class FaultMetricsPanel : public PanelTest {
  protected:
    void showWallFault() {
        std::vector<std::int64_t> ids;
        for (std::int64_t id = 2; id <= 64; id += 4)
            ids.push_back(id);
        session.apply({{"op", "fault.create"}, {"name", "F1"}, {"ids", ids}});
        wb().selection().faults = {"F1"};
        headless.showPanel(wb(), ui::panel_ids::kFaults);
        headless.settle(wb());
    }
};

TEST_F(FaultMetricsPanel, PlotFollowsTheFrameAndGoesToTheFrameClicked) {
    openLattice();
    showWallFault();
    ASSERT_TRUE(headless.has(wb(), "faults.metrics.plot"));
    EXPECT_FALSE(headless.has(wb(), "faults.metrics.progress")); // computed and shown
    EXPECT_TRUE(headless.emitted().empty()) << "computing metrics is no command";

    // A click near the right end goes to the last frame.
    const ui::ItemRect plot = headless.rect(wb(), "faults.metrics.plot");
    headless.clickAt(wb(), plot.x1 - 12, plot.cy());
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 2}}}));
    EXPECT_EQ(session.state().frame, 2u);

    // A drag to the left end: the views follow while held, one frame.set on release.
    headless.clearEmitted();
    std::size_t shownWhileHeld = 99;
    headless.drag(wb(), plot.x1 - 12, plot.cy(), plot.x0 + 2, plot.cy(), 4, 0, [&] {
        shownWhileHeld = wb().displayFrame();
        EXPECT_TRUE(headless.emitted().empty());
    });
    EXPECT_EQ(shownWhileHeld, 0u);
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 0}}}));

    // Another metric from the combo; the plot stays (no recomputation, no command).
    headless.clearEmitted();
    headless.click(wb(), "faults.metrics.metric");
    headless.frames(wb(), 2);
    headless.click(wb(), "faults.metrics.metric.count");
    headless.frames(wb(), 2);
    EXPECT_FALSE(wb().jobs().busy());
    EXPECT_TRUE(headless.emitted().empty());
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.plot"));

    // Adding members starts a job for the new membership; undo brings back the cached one.
    session.apply({{"op", "fault.add"}, {"name", "F1"}, {"ids", {1}}});
    headless.frames(wb(), 1);
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.progress") || !wb().jobs().busy());
    headless.settle(wb());
    EXPECT_FALSE(headless.has(wb(), "faults.metrics.progress"));
    session.apply({{"op", "undo"}});
    headless.frames(wb(), 2);
    EXPECT_FALSE(wb().jobs().busy());
    EXPECT_FALSE(headless.has(wb(), "faults.metrics.progress"));
}

// Issue 41: the plot drew the fixed members' metrics from frame 0, before their fault formed.
// A series says from which frame its members have broken bonds; without the variable, from 0.
TEST(FaultMetricsCache, ASeriesSaysFromWhichFrameItsFaultFormed) {
    auto loader = [](std::size_t k) {
        core::Frame f = sheetAt(k);
        core::AttributeColumn bonds;
        bonds.name = "broken_bonds";
        bonds.type = core::ColumnType::Int32;
        bonds.ints.assign(f.size(), 0);
        if (k >= 2)
            bonds.ints[4] = 1; // the centre sphere breaks at frame 2
        f.attributes = {bonds};
        f.finalize();
        return f;
    };
    auto broken = core::Dataset::fromLoader(4, loader);
    auto plain = core::Dataset::fromLoader(4, sheetAt);
    ui::JobRunner jobs;
    ui::FaultMetricsCache cache;
    core::Fault f = faultOf("F1", {1, 2, 3, 4, 5, 6, 7, 8, 9});
    const core::Fault* faults[] = {&f};
    cache.request(jobs, 0, broken, faults);
    jobs.waitAll();
    jobs.poll();
    ASSERT_NE(cache.find(broken, f), nullptr);
    EXPECT_EQ(cache.find(broken, f)->formedFrom(), 2u);
    cache.request(jobs, 0, plain, faults);
    jobs.waitAll();
    jobs.poll();
    ASSERT_NE(cache.find(plain, f), nullptr);
    EXPECT_EQ(cache.find(plain, f)->formedFrom(), 0u);
}

TEST_F(FaultMetricsPanel, PlotMarksWhenTheFaultsAppearedLinkedAndSplit) {
    openLattice();
    // Only the wall x = 1 is visible: one fault, there from the first frame.
    session.apply({{"op", "box.add"}, {"name", "wall"}, {"min", {1, 0, 0}}, {"max", {1, 3, 3}}});
    showWallFault();
    EXPECT_FALSE(headless.has(wb(), "faults.metrics.events.shown"));
    headless.clearEmitted();
    headless.click(wb(), "faults.metrics.events");
    headless.settle(wb());
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.events.shown"));
    EXPECT_TRUE(headless.emitted().empty()) << "finding events is no command";
    // Growth: the plot follows the candidates (the same wall here, so the same plot).
    headless.click(wb(), "faults.metrics.growth");
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.plot"));
    EXPECT_TRUE(headless.emitted().empty());
    // Another selection of visible spheres: those events are not shown for it; the faults are
    // followed again, saying so in the panel (issue 41: results changed or vanished without a
    // word), not in the status bar, where it hid what changed them.
    const std::string before = wb().lastMessage();
    session.apply({{"op", "box.set"}, {"name", "wall"}, {"enabled", false}});
    // One frame: the frame that sees the change starts following again and says so; on this
    // small lattice the job can be done by the next (under load it was, 11 runs in 30).
    headless.frames(wb(), 1);
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.following_again"));
    EXPECT_EQ(wb().lastMessage(), before);
    headless.settle(wb());
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.has(wb(), "faults.metrics.events.shown"));
}

// Walkthrough of issue 41: with the faults followed through time, moving spheres from one
// fault to another said "The faults shown changed: following them through time again" where
// "Moved 4 from F1 to F2" should have been; the status keeps what the move says.
TEST_F(FaultMetricsPanel, AMoveStillSaysWhatMovedWhileFaultsAreFollowed) {
    openLattice();
    showWallFault();
    session.apply({{"op", "fault.create"}, {"name", "F2"}, {"ids", {1, 5}}});
    wb().selection().faults.clear();
    headless.settle(wb());
    headless.click(wb(), "faults.metrics.events");
    headless.settle(wb());
    ASSERT_TRUE(headless.has(wb(), "faults.metrics.events.shown"));
    wb().emit({{"op", "fault.add"}, {"name", "F2"}, {"ids", {2, 6, 10, 14}}});
    headless.frames(wb(), 3);
    EXPECT_NE(wb().lastMessage().find("Moved 4 from F1"), std::string::npos) << wb().lastMessage();
    headless.settle(wb());
    EXPECT_NE(wb().lastMessage().find("Moved 4 from F1"), std::string::npos) << wb().lastMessage();
}
