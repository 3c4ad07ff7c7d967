// Cutting boxes (issue 39: the feature had no test file of its own): the box itself, its JSON
// (box.add / box.set fields and a session's boxes[]), and the journal ops with undo. What boxes
// do to visibility is in visibility_test.cpp; dragging a face in view_geometry_test.cpp.
#include "core/selection/cutting_box.hpp"
#include "core/session/command_args.hpp"
#include "core/session/items/box_codec.hpp"
#include "core/session/session.hpp"

#include "lattice_dump.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;

TEST(CuttingBox, ContainsItsBoundsInclusively) {
    CuttingBox b{"north", {0, 5, 0}, {10, 8, 2}, BoxMode::Keep, true};
    EXPECT_TRUE(b.contains(0, 5, 0));
    EXPECT_TRUE(b.contains(10, 8, 2));
    EXPECT_TRUE(b.contains(5, 6.5, 1));
    EXPECT_FALSE(b.contains(10.0001, 6, 1));
    EXPECT_FALSE(b.contains(5, 4.9999, 1));
}

TEST(CuttingBox, ModesHaveJournalNames) {
    EXPECT_EQ(boxModeName(BoxMode::Keep), "keep");
    EXPECT_EQ(boxModeName(BoxMode::Cut), "cut");
    EXPECT_EQ(parseBoxMode("cut"), BoxMode::Cut);
    EXPECT_EQ(parseBoxMode("Keep"), std::nullopt); // the journal's names are lower case
}

TEST(CuttingBox, JsonRoundTripAndValidation) {
    const CuttingBox b{"slab", {1, 2, 3}, {4, 5, 6}, BoxMode::Cut, false};
    const Json j = items::toJson(b);
    EXPECT_EQ(j["mode"], "cut");
    EXPECT_EQ(j["enabled"], false);
    CuttingBox back;
    items::patch(back, items::ItemReader(j));
    EXPECT_EQ(back, b);
    CuttingBox inverted = b;
    inverted.max[1] = 0; // max below min
    EXPECT_THROW(items::validate(inverted), items::ItemError);
}

TEST(CuttingBox, OpsChangeBoxesAndUndoPutsThemBack) {
    faultline::test::TempDir dir;
    Session s;
    s.apply({{"op", "data.open"},
             {"paths", {dir.write("lattice.dump", faultline::test::latticeDump())}}});
    s.apply({{"op", "box.add"}, {"name", "west"}, {"min", {0, 0, 0}}, {"max", {1, 3, 3}}});
    EXPECT_EQ(s.visibility().visibleCount, 32u);
    s.apply({{"op", "box.set"}, {"name", "west"}, {"mode", "cut"}});
    EXPECT_EQ(s.visibility().visibleCount, 32u); // the other half
    s.apply({{"op", "box.set"}, {"name", "west"}, {"enabled", false}});
    EXPECT_EQ(s.visibility().visibleCount, 64u);
    EXPECT_THROW(
        s.apply({{"op", "box.add"}, {"name", "west"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}}),
        CommandError); // the name is taken
    EXPECT_THROW(s.apply({{"op", "box.set"}, {"name", "east"}, {"enabled", true}}), CommandError);
    s.apply({{"op", "box.remove"}, {"name", "west"}});
    EXPECT_TRUE(s.state().boxes.empty());
    s.undo(); // remove
    s.undo(); // enabled
    ASSERT_EQ(s.state().boxes.size(), 1u);
    EXPECT_TRUE(s.state().boxes[0].enabled);
    EXPECT_EQ(s.state().boxes[0].mode, BoxMode::Cut);
    s.undo(); // mode
    s.undo(); // add
    EXPECT_TRUE(s.state().boxes.empty());
    EXPECT_EQ(s.visibility().visibleCount, 64u);
}
