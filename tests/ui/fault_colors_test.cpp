// Spheres in their fault's colour (the view variable "faults") and the Faults panel's candidates:
// found on request, shown in distinct colours in the main view, accepted one by one or all.
#include "panel_fixture.hpp"

#include "core/faults/candidates.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/viewport/category_colors.hpp"

#include <algorithm>

using namespace faultline;
using namespace faultline::test;
using core::Json;

namespace {

// Two walls of the lattice, x = 0 and x = 3 (16 spheres each), are all that is visible.
void twoWalls(core::Session& session) {
    session.apply(Json::parse(R"({"op":"box.add","name":"west","min":[0,0,0],"max":[0,3,3]})"));
    session.apply(Json::parse(R"({"op":"box.add","name":"east","min":[3,0,0],"max":[3,3,3]})"));
}

} // namespace

// Candidates found with every sphere visible are pieces of the whole model: the section says
// so and what to narrow them by (a walkthrough on LIGGGHTS' run found three slabs of the block).
TEST_F(PanelTest, CandidatesOfTheWholeModelSayToNarrowTheSpheresFirst) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    findCandidates();
    ASSERT_TRUE(wb().selection().candidates.has_value());
    EXPECT_TRUE(headless.has(wb(), "candidates.all_visible"));
    twoWalls(session);
    findCandidates();
    ASSERT_TRUE(wb().selection().candidates.has_value());
    EXPECT_FALSE(headless.has(wb(), "candidates.all_visible"));
}

TEST_F(PanelTest, CandidatesAreShownInTheirColoursAndAcceptedAsFaults) {
    openLattice();
    twoWalls(session);
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.click(wb(), "candidates.find");
    headless.settle(wb()); // found in a background job
    ASSERT_TRUE(wb().selection().candidates.has_value());
    ASSERT_EQ(wb().selection().candidates->set.candidates.size(), 2u);
    headless.frames(wb(), 2);
    const ui::ViewDisplay* d = wb().mainDisplay();
    ASSERT_EQ(d->palette.size(), 3u); // none + two candidates
    EXPECT_EQ(d->colorTitle, "candidates");
    // Sphere id 1 (x = 0) and id 4 (x = 3) are in different candidates; id 2 (x = 1) in none.
    const auto& v = d->colorColumn->floats;
    const auto row = [&](std::int64_t id) { return *d->frame->rowOf(id); };
    EXPECT_NE(v[row(1)], v[row(4)]);
    EXPECT_GT(v[row(1)], 1.0f);
    EXPECT_FLOAT_EQ(v[row(2)], 0.5f);

    headless.clearEmitted();
    headless.click(wb(), "candidates.accept.1");
    const auto created = headless.emitted("fault.create");
    ASSERT_EQ(created.size(), 1u);
    EXPECT_EQ(created[0]["name"], "C1"); // as the list and the legend name it
    EXPECT_EQ(created[0]["ids"].size(), 16u);
    ASSERT_NE(session.state().fault("C1"), nullptr);
    EXPECT_EQ(wb().selection().faults, (std::set<std::string>{"C1"}));
    // Accept all: the journal's op with the same parameters, under another prefix.
    session.undo();
    headless.frames(wb(), 2);
    headless.clearEmitted();
    headless.click(wb(), "candidates.accept_all");
    ASSERT_EQ(headless.emitted("fault.candidates").size(), 1u);
    EXPECT_EQ(headless.emitted("fault.candidates")[0]["min_size"], 10);
    EXPECT_EQ(session.state().faults.size(), 2u);
    EXPECT_NE(session.state().fault("C1"), nullptr); // the journal's default prefix, not F's
    EXPECT_FALSE(wb().selection().candidates.has_value());
}

// Issue 39: the preview is found in the frame the main view shows, the op in the session's
// current frame. With the main view a frame behind, Accept all still makes the faults shown.
// "New from visible" takes every visible sphere: a fault all of whose spheres are visible is
// left empty, and is deleted in the same step (one undo brings it back).
TEST_F(PanelTest, NewFromVisibleDeletesTheFaultItEmpties) {
    openLattice();
    std::vector<std::int64_t> west; // the x = 0 wall
    for (std::int64_t id = 1; id <= 64; id += 4)
        west.push_back(id);
    session.apply({{"op", "fault.create"}, {"name", "W"}, {"ids", west}});
    twoWalls(session);
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.frames(wb(), 2);
    headless.click(wb(), "faults.create");
    ASSERT_NE(session.state().fault("F1"), nullptr);
    EXPECT_EQ(session.state().fault("F1")->ids.size(), 32u);
    EXPECT_EQ(session.state().fault("W"), nullptr) << "an empty W was left in the list";
    session.undo();
    ASSERT_NE(session.state().fault("W"), nullptr);
    EXPECT_EQ(session.state().fault("W")->ids.size(), 16u);
    EXPECT_EQ(session.state().fault("F1"), nullptr);
}

// Issue 39: the main view's visible spheres and the session's (what ops such as
// fault.candidates read) are one result from one cache, not two computations that may differ.
TEST_F(PanelTest, TheMainViewAndTheOpsShareOneVisibility) {
    openLattice();
    twoWalls(session);
    headless.frames(wb(), 2);
    ASSERT_NE(wb().mainDisplay()->visibility, nullptr);
    EXPECT_EQ(wb().mainDisplay()->visibility.get(), &session.visibility());
    EXPECT_EQ(session.visibility().visibleCount, 32u);
}

TEST_F(PanelTest, AcceptAllMakesTheCandidatesShownWhenTheMainViewShowsAnotherFrame) {
    openLattice();
    // strain = x / 3 + frame: in [1.9, 2.1] the x = 3 wall in frame 1, the x = 0 wall in frame 2.
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    session.apply(
        Json::parse(R"({"op":"threshold.add","variable":"strain","low":1.9,"high":2.1})"));
    session.apply(Json::parse(R"({"op":"view.set","name":"main","offset":-1})"));
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->shownFrame, 1u);
    headless.click(wb(), "candidates.find");
    headless.settle(wb());
    ASSERT_TRUE(wb().selection().candidates.has_value());
    ASSERT_EQ(wb().selection().candidates->set.candidates.size(), 1u);
    std::vector<std::int64_t> shown = wb().selection().candidates->set.candidates[0].ids;
    std::sort(shown.begin(), shown.end());
    EXPECT_EQ(shown.front(), 4); // the x = 3 wall: ids 4, 8, ..., 64
    headless.frames(wb(), 2);
    headless.click(wb(), "candidates.accept_all");
    ASSERT_EQ(session.state().faults.size(), 1u);
    std::vector<std::int64_t> made = session.state().faults[0].ids;
    std::sort(made.begin(), made.end());
    EXPECT_EQ(made, shown);
    EXPECT_EQ(session.state().frame, 2u); // the current frame as it was
    session.undo();                       // one step
    EXPECT_TRUE(session.state().faults.empty());
    EXPECT_EQ(session.state().frame, 2u);
}

// Issue 41: accepting a candidate took spheres out of existing faults with only a status line
// after the fact. Each candidate row says beforehand how many of its spheres faults hold.
TEST_F(PanelTest, CandidateRowsSayWhichSpheresAcceptingWouldMove) {
    openLattice();
    twoWalls(session);
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.click(wb(), "candidates.find");
    headless.settle(wb());
    ASSERT_EQ(wb().selection().candidates->set.candidates.size(), 2u);
    headless.frames(wb(), 2);
    EXPECT_FALSE(headless.has(wb(), "candidates.overlap.1"));
    EXPECT_FALSE(headless.has(wb(), "candidates.overlap.2"));
    // Spheres 1 (x = 0) and 4 (x = 3): one in each wall.
    session.apply(Json::parse(R"({"op":"fault.create","name":"W","ids":[1,4]})"));
    headless.frames(wb(), 2);
    headless.click(wb(), "faults.section.Metrics over time"); // folded: the list in view
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.has(wb(), "candidates.overlap.1"));
    EXPECT_TRUE(headless.has(wb(), "candidates.overlap.2"));
    headless.click(wb(), "candidates.accept.1");
    headless.frames(wb(), 2);
    EXPECT_EQ(session.state().fault("W")->ids.size(), 1u);    // one moved into C1
    EXPECT_FALSE(headless.has(wb(), "candidates.overlap.1")); // accepted
    EXPECT_TRUE(headless.has(wb(), "candidates.overlap.2"));
    // Accepting the other takes W's last sphere: W goes too, in the same undo step (a
    // walkthrough: an emptied fault stayed in the list, the legend and the metrics).
    headless.click(wb(), "candidates.accept.2");
    headless.frames(wb(), 2);
    EXPECT_EQ(session.state().fault("W"), nullptr);
    EXPECT_EQ(session.state().faults.size(), 2u);
    session.undo();
    ASSERT_NE(session.state().fault("W"), nullptr);
    EXPECT_EQ(session.state().fault("W")->ids.size(), 1u);
}

TEST_F(PanelTest, TheFaultsVariableColoursMembersInTheirFaultsColour) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"A","ids":[1,2],"color":[1,0,0]})"));
    session.apply(Json::parse(R"({"op":"fault.create","name":"B","ids":[2,3],"color":[0,0,1]})"));
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"faults"})"));
    headless.frames(wb(), 2);
    const ui::ViewDisplay* d = wb().mainDisplay();
    ASSERT_EQ(d->palette.size(), 3u);
    EXPECT_EQ(d->palette[1], glm::vec3(1, 0, 0));
    const auto& v = d->colorColumn->floats;
    const auto row = [&](std::int64_t id) { return *d->frame->rowOf(id); };
    EXPECT_FLOAT_EQ(v[row(1)], 1.5f); // A
    EXPECT_FLOAT_EQ(v[row(2)], 2.5f); // moved to B when B took it (one fault per sphere)
    EXPECT_FLOAT_EQ(v[row(3)], 2.5f); // B
    EXPECT_FLOAT_EQ(v[row(4)], 0.5f); // none
    // Issue 41, item 10: the legend names each fault in its colour, spheres in none last.
    ASSERT_EQ(d->legend.size(), 3u);
    EXPECT_EQ(d->legend[0].name, "A");
    EXPECT_EQ(d->legend[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(d->legend[1].name, "B");
    EXPECT_EQ(d->legend[2].name, "no fault");
    // Recolouring a fault recolours at once.
    session.apply(Json::parse(R"({"op":"fault.set","name":"A","color":[0,1,0]})"));
    headless.frames(wb(), 2);
    EXPECT_EQ(wb().mainDisplay()->palette[1], glm::vec3(0, 1, 0));
    EXPECT_EQ(wb().mainDisplay()->legend[0].color, glm::vec3(0, 1, 0));
}

TEST_F(PanelTest, SplitCutsTheSelectedFaultIntoItsConnectedPieces) {
    openLattice();
    twoWalls(session);
    session.apply(Json::parse(R"({"op":"fault.create","name":"W","from":"visible"})"));
    wb().selection().faults = {"W"};
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.clearEmitted();
    headless.click(wb(), "faults.split");
    ASSERT_EQ(headless.emitted("fault.split").size(), 1u);
    ASSERT_NE(session.state().fault("W.1"), nullptr);
    ASSERT_NE(session.state().fault("W.2"), nullptr);
    EXPECT_EQ(session.state().fault("W.1")->ids.size(), 16u);
    EXPECT_EQ(wb().selection().faults, (std::set<std::string>{"W.1"}));
    // The status line says what happened, and what became of small pieces.
    EXPECT_NE(
        wb().lastMessage().find("Split W into 2 faults; pieces under 10 spheres stay with W.1"),
        std::string::npos)
        << wb().lastMessage();
}

// Issue 27: undo and redo name what they revert in the status line; frames are no undo steps.
TEST_F(PanelTest, UndoAndRedoSayWhatTheyRevert) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","ids":[1,2,3]})"));
    session.apply(Json::parse(R"({"op":"frame.set","frame":1})")); // no undo step
    wb().emit({{"op", "undo"}});
    headless.frames(wb(), 1);
    EXPECT_EQ(wb().lastMessage(), "Undone: make fault F1 (3 spheres)");
    EXPECT_EQ(session.state().frame, 1u);
    wb().emit({{"op", "redo"}});
    headless.frames(wb(), 1);
    EXPECT_EQ(wb().lastMessage(), "Redone: make fault F1 (3 spheres)");
    EXPECT_EQ(session.undoLabel(), "make fault F1 (3 spheres)");
}

// Issue 41, item 10: double-clicking a fault's name renames it in place.
TEST_F(PanelTest, DoubleClickRenamesAFaultInPlace) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"C2","ids":[1,2]})"));
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.click(wb(), "faults.row.C2");
    headless.click(wb(), "faults.row.C2");
    headless.frames(wb(), 2);
    ASSERT_TRUE(headless.has(wb(), "faults.rename.C2"));
    headless.key(wb(), GLFW_KEY_A, true);
    headless.type(wb(), "Graben W");
    headless.key(wb(), GLFW_KEY_ENTER);
    headless.frames(wb(), 2);
    EXPECT_NE(session.state().fault("Graben W"), nullptr);
    EXPECT_EQ(session.state().fault("C2"), nullptr);
    EXPECT_FALSE(headless.has(wb(), "faults.rename.Graben W"));
}

// Issue 37: a sub-horizontal candidate (a real run's creeping surface layer) is flagged "flat" in
// the list, and accepting it says so in the fault's notes; the lattice's walls are not flagged.
TEST_F(PanelTest, FlatCandidatesAreFlaggedAndSayWhatTheyMayBe) {
    openLattice();
    twoWalls(session);
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    findCandidates();
    ASSERT_EQ(wb().selection().candidates->set.candidates.size(), 2u);
    EXPECT_FALSE(headless.has(wb(), "candidates.flat.1"));
    EXPECT_FALSE(headless.has(wb(), "candidates.flat.2"));
    session.apply(Json::parse(R"({"op":"box.remove","name":"west"})"));
    session.apply(Json::parse(R"({"op":"box.set","name":"east","min":[0,0,0],"max":[3,3,0]})"));
    findCandidates();
    ASSERT_EQ(wb().selection().candidates->set.candidates.size(), 1u);
    EXPECT_TRUE(headless.has(wb(), "candidates.flat.1"));
    headless.click(wb(), "candidates.accept.1");
    const core::Fault* floor = session.state().fault("C1");
    ASSERT_NE(floor, nullptr);
    EXPECT_NE(floor->notes.find("sub-horizontal: dips 0.0 degrees"), std::string::npos)
        << floor->notes;
}
