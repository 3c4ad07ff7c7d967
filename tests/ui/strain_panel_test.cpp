// Issue 36: the Data panel's "Strain from motion" adds strain.add as typed (incremental or
// cumulative, cutoff, prefix), its variables reach the views' frames, and Remove takes them away.
// The first Add colours the plain main view by the new shear strain; later ones leave it.
#include "panel_fixture.hpp"

#include "core/data/frame_cache.hpp"
#include "ui/dock/panel_ids.hpp"

#include <chrono>
#include <fstream>
#include <thread>

namespace faultline::test {
namespace {

using core::Json;

TEST_F(PanelTest, StrainFromMotionSectionAddsAndRemovesVariables) {
    openLattice(); // 3 frames: one frame before each (four would leave none with a value)
    headless.showPanel(wb(), ui::panel_ids::kData);
    ASSERT_TRUE(session.state().view("main")->colorVariable.empty());
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    // The main view was in plain colour: it shows the new shear strain, in the same step.
    ASSERT_EQ(headless.emitted("batch").size(), 1u) << wb().lastMessage();
    EXPECT_EQ(headless.emitted("batch")[0],
              (Json{{"op", "batch"},
                    {"commands",
                     {{{"op", "strain.add"}, {"since_offset", -1}, {"prefix", "inc_"}},
                      {{"op", "color.set"},
                       {"view", "main"},
                       {"variable", "inc_shear_strain"},
                       {"range_mode", "percentile"}}}}}));
    ASSERT_EQ(session.state().strains.size(), 1u);
    EXPECT_EQ(session.state().view("main")->colorVariable, "inc_shear_strain");
    // From the 1st to the 99th percentile: a few grains thrown out wash out nothing.
    EXPECT_EQ(session.state().view("main")->rangeMode, core::RangeMode::Percentile);
    EXPECT_EQ(session.undoLabel(), "add strain from motion (inc_*), coloured by inc_shear_strain");
    ASSERT_TRUE(session.undo());
    EXPECT_TRUE(session.state().strains.empty());
    EXPECT_TRUE(session.state().view("main")->colorVariable.empty());
    ASSERT_TRUE(session.redo());
    headless.frames(wb(), 2);
    headless.settle(wb());
    const ui::ViewDisplay* main = wb().mainDisplay();
    ASSERT_NE(main->frame, nullptr);
    EXPECT_NE(main->frame->attribute("inc_shear_strain"), nullptr);

    // Cumulative, a typed cutoff: the prefix follows the kind until the user types one. The
    // view is coloured already: strain.add alone.
    headless.clearEmitted();
    headless.click(wb(), "strain.cumulative");
    headless.retype(wb(), "strain.cutoff", "1.2");
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("strain.add").size(), 1u) << wb().lastMessage();
    EXPECT_EQ(headless.emitted("strain.add")[0],
              (Json{{"op", "strain.add"}, {"since_frame", 0}, {"cutoff", 1.2}}));
    // The same again is refused with words in the status line; nothing changes.
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    EXPECT_TRUE(wb().lastMessageIsError());
    EXPECT_NE(wb().lastMessage().find("exist already"), std::string::npos) << wb().lastMessage();
    EXPECT_EQ(session.state().strains.size(), 2u);

    headless.clearEmitted();
    headless.click(wb(), "strain.remove.inc_");
    headless.settle(wb());
    EXPECT_EQ(headless.emitted("strain.remove"),
              (std::vector<Json>{{{"op", "strain.remove"}, {"prefix", "inc_"}}}));
    headless.frames(wb(), 2);
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->frame->attribute("inc_shear_strain"), nullptr);
    EXPECT_NE(wb().mainDisplay()->frame->attribute("shear_strain"), nullptr);
}

// Radii in another unit than the centres (40 beside a spacing of 1): the Data panel says so under
// the frame, and Add with the automatic cutoff is refused with words that say what to give.
TEST_F(PanelTest, RadiiFarLargerThanTheSpacingAreNotedAndAskForACutoff) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kData);
    headless.frames(wb(), 2);
    EXPECT_FALSE(headless.has(wb(), "data.radii_note")); // a packing: nothing to say
    std::ofstream(dir.file("mm.dump")) << test::shearedLatticeDump(14, "20");
    wb().opener().openData({dir.file("mm.dump")});
    headless.settle(wb());
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.has(wb(), "data.radii_note"));
    headless.clearEmitted();
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    EXPECT_TRUE(wb().lastMessageIsError());
    // In words: what could not be done, then why (not the op's name).
    EXPECT_EQ(wb().lastMessage().rfind("Could not add strain from motion (inc_*), coloured by "
                                       "inc_shear_strain: give \"cutoff\", e.g. 1.49 (",
                                       0),
              0u)
        << wb().lastMessage();
    EXPECT_TRUE(session.state().strains.empty());
    headless.retype(wb(), "strain.cutoff", "1.49");
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    ASSERT_EQ(session.state().strains.size(), 1u);
    EXPECT_EQ(session.state().strains[0].cutoff, 1.49);
}

// With the frame cache off, the Data panel says why the other frames are not readied in the
// background: each one's strain is computed when it is shown.
TEST_F(PanelTest, TheStrainSectionSaysWhyFramesAreNotReadiedInTheBackground) {
    struct Restore {
        std::shared_ptr<core::FrameCache> before = core::FrameCache::processDefault();
        ~Restore() { core::FrameCache::setProcessDefault(before); }
    } restore;
    core::FrameCacheSettings off;
    off.enabled = false;
    core::FrameCache::setProcessDefault(std::make_shared<core::FrameCache>(off));
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kData);
    EXPECT_FALSE(headless.has(wb(), "strain.held"));
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    for (int k = 0; k < 400 && !headless.has(wb(), "strain.held"); ++k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        headless.frames(wb(), 1);
    }
    EXPECT_TRUE(headless.has(wb(), "strain.held"));
    EXPECT_FALSE(headless.has(wb(), "strain.progress"));
}

// After strain.remove the view keeps its variable (undo and a new strain.add bring it back),
// but its colour button says the frame lacks it instead of naming a colour map over spheres in
// one colour.
TEST_F(PanelTest, TheColourButtonSaysWhenTheFrameLacksItsVariable) {
    openLattice();
    session.apply({{"op", "strain.add"}, {"since_frame", 0}});
    session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "shear_strain"}});
    headless.frames(wb(), 2);
    headless.settle(wb());
    ASSERT_NE(wb().mainDisplay()->frame->attribute("shear_strain"), nullptr);
    EXPECT_TRUE(headless.has(wb(), "view.colour.main"));
    EXPECT_FALSE(headless.has(wb(), "view.colour.missing.main"));

    session.apply({{"op", "strain.remove"}, {"prefix", ""}});
    headless.frames(wb(), 2);
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->frame->attribute("shear_strain"), nullptr);
    EXPECT_EQ(session.state().view("main")->colorVariable, "shear_strain");
    EXPECT_TRUE(headless.has(wb(), "view.colour.missing.main"));

    ASSERT_TRUE(session.undo());
    headless.frames(wb(), 2);
    headless.settle(wb());
    EXPECT_FALSE(headless.has(wb(), "view.colour.missing.main"));
    // Categories and differences have no variable of their own to miss.
    session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "faults"}});
    headless.frames(wb(), 2);
    EXPECT_FALSE(headless.has(wb(), "view.colour.missing.main"));
}

// Incremental strain has no value on a frame without one that far back: the spheres are grey,
// and a view showing such a frame (the first frame, or a view bound a frame back) drew a legend
// from -0.5 to 0.5 for values no sphere has. It now draws none and its button says why.
TEST_F(PanelTest, AViewWhoseVariableHasNoValueInItsFrameSaysSo) {
    openLattice();
    session.apply({{"op", "strain.add"}, {"since_offset", -1}, {"prefix", "inc_"}});
    session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "inc_shear_strain"}});
    session.apply({{"op", "frame.set"}, {"frame", 0}});
    headless.frames(wb(), 2);
    headless.settle(wb());
    ASSERT_NE(wb().mainDisplay()->frame->attribute("inc_shear_strain"), nullptr);
    EXPECT_TRUE(wb().mainDisplay()->colorHasNoValue);
    EXPECT_TRUE(headless.has(wb(), "view.colour.novalue.main"));
    EXPECT_FALSE(headless.has(wb(), "view.colour.missing.main"));

    // Faults' colours (categories) have no values to miss: not marked, though the last
    // colouring was.
    session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "faults"}});
    headless.frames(wb(), 2);
    EXPECT_FALSE(wb().mainDisplay()->colorHasNoValue);
    EXPECT_FALSE(headless.has(wb(), "view.colour.novalue.main"));
    session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "inc_shear_strain"}});
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().mainDisplay()->colorHasNoValue);

    session.apply({{"op", "frame.set"}, {"frame", 1}});
    headless.frames(wb(), 2);
    headless.settle(wb());
    EXPECT_FALSE(wb().mainDisplay()->colorHasNoValue);
    EXPECT_FALSE(headless.has(wb(), "view.colour.novalue.main"));
}

// A view coloured by displacement has no variable, yet is not plain: Add leaves its colours.
TEST_F(PanelTest, StrainAddLeavesADisplacementColouringAlone) {
    openLattice();
    session.apply({{"op", "color.set"},
                   {"view", "main"},
                   {"difference", "displacement"},
                   {"since_frame", 0}});
    headless.showPanel(wb(), ui::panel_ids::kData);
    headless.click(wb(), "strain.add");
    headless.settle(wb());
    EXPECT_TRUE(headless.emitted("batch").empty());
    ASSERT_EQ(headless.emitted("strain.add").size(), 1u) << wb().lastMessage();
    EXPECT_EQ(session.state().view("main")->difference.mode,
              core::ColorDifference::Mode::Displacement);
}

} // namespace
} // namespace faultline::test

namespace faultline::test {
namespace {

// Issue 41, item 13: a threshold on a variable the data lacks says so where it is, with the
// name it probably meant.
TEST_F(PanelTest, AThresholdOnAMissingVariableSaysSo) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kThresholds);
    session.apply(
        core::Json::parse(R"({"op":"threshold.add","variable":"strian","low":0,"high":1})"));
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.has(wb(), "thresholds.missing.strian"));
    session.apply(
        core::Json::parse(R"({"op":"threshold.add","variable":"strain","low":0,"high":1})"));
    headless.frames(wb(), 2);
    EXPECT_FALSE(headless.has(wb(), "thresholds.missing.strain"));
}

} // namespace
} // namespace faultline::test
