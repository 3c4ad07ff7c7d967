// Headless runs of the Faults, Timeline and Viewports panels and of the dock: scripted input,
// checking the commands emitted (and that drags preview without commands until released).
#include "panel_fixture.hpp"

#include "core/session/journal.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <filesystem>
#include <fstream>

using namespace faultline;
using namespace faultline::test;
using core::Json;

TEST_F(PanelTest, FaultsPanelCreatesHidesFiltersAndDeletes) {
    openLattice();
    session.apply(Json::parse(R"({"op":"threshold.add","variable":"strain","low":0.5})"));
    headless.frames(wb(), 2);
    EXPECT_EQ(visible(), 32u);
    headless.showPanel(wb(), ui::panel_ids::kFaults);
    headless.click(wb(), "faults.create");
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "fault.create"}, {"name", "F1"}, {"from", "visible"}}}));
    ASSERT_NE(session.state().fault("F1"), nullptr);
    EXPECT_EQ(session.state().fault("F1")->ids.size(), 32u);
    EXPECT_EQ(wb().selection().faults, std::set<std::string>{"F1"});

    headless.clearEmitted();
    session.apply(Json::parse(R"({"op":"threshold.remove","variable":"strain"})"));
    headless.frames(wb(), 2);
    headless.click(wb(), "faults.visible.F1");
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "fault.set"}, {"name", "F1"}, {"visible", false}}}));
    EXPECT_EQ(visible(), 32u); // the hidden fault's members are hidden

    headless.clearEmitted();
    headless.click(wb(), "faults.filter");
    headless.frames(wb(), 2);
    headless.click(wb(), "faults.filter.only.F1");
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "fault.filter"}, {"mode", "only"}, {"fault", "F1"}}}));
    EXPECT_EQ(visible(), 32u);

    headless.clearEmitted();
    headless.click(wb(), "faults.delete");
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "fault.delete"}, {"name", "F1"}}}));
    EXPECT_TRUE(session.state().faults.empty());
    EXPECT_EQ(visible(), 64u); // deleting the only-shown fault resets the filter
}

TEST_F(PanelTest, TimelineStepsScrubsAndPlaysWithOneCommandPerChange) {
    openLattice();
    headless.click(wb(), "timeline.next");
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 1}}}));
    EXPECT_EQ(session.state().frame, 1u);
    headless.settle(wb());

    // Scrub to the end: the views follow, one frame.set on release.
    headless.clearEmitted();
    const ui::ItemRect r = headless.rect(wb(), "timeline.slider");
    std::size_t shownWhileHeld = 0;
    headless.drag(wb(), r.cx(), r.cy(), r.x1 - 2, r.cy(), 4, 0, [&] {
        wb().frames().waitIdle();
        headless.frames(wb(), 2);
        shownWhileHeld = wb().mainDisplay()->shownFrame;
        EXPECT_TRUE(headless.emitted().empty());
    });
    EXPECT_EQ(shownWhileHeld, 2u);
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 2}}}));

    // Play: frames advance with no commands; pausing commits the frame shown.
    headless.clearEmitted();
    headless.key(wb(), GLFW_KEY_HOME);
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 0}}}));
    headless.clearEmitted();
    headless.click(wb(), "timeline.play");
    EXPECT_TRUE(wb().playback().playing);
    std::set<std::size_t> seen;
    for (int k = 0; k < 60; ++k) { // one second at 5 frames per second
        wb().frames().waitIdle();
        headless.frames(wb());
        seen.insert(wb().mainDisplay()->shownFrame);
    }
    EXPECT_EQ(seen, (std::set<std::size_t>{0, 1, 2}));
    EXPECT_TRUE(headless.emitted().empty());
    headless.key(wb(), GLFW_KEY_SPACE);
    EXPECT_FALSE(wb().playback().playing);
    const auto sets = headless.emitted("frame.set");
    EXPECT_LE(sets.size(), 1u); // none when it paused on the session's frame
    EXPECT_EQ(session.state().frame, wb().mainDisplay()->shownFrame);

    headless.clearEmitted();
    session.apply(Json::parse(R"({"op":"frame.set","frame":1})"));
    headless.key(wb(), GLFW_KEY_LEFT);
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "frame.set"}, {"frame", 0}}}));
}

TEST_F(PanelTest, ViewportsAddAViewAndCameraDragsCommitOnRelease) {
    openLattice();
    headless.click(wb(), "viewports.add");
    // The view, then every view fitted again to its narrower cell (walkthrough of issue 41:
    // the legend covered the block's east end until Fit was pressed).
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "view.add"}, {"name", "view 2"}, {"offset", -2}},
                                 {{"op", "camera.set"}, {"view", "main"}, {"distance", 0.0}},
                                 {{"op", "camera.set"}, {"view", "view 2"}, {"distance", 0.0}}}));
    EXPECT_EQ(session.undoLabel().find("camera"), std::string::npos)
        << "undo takes the view away, not a camera move: " << session.undoLabel();
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    headless.settle(wb());
    ASSERT_EQ(wb().views().size(), 2u);
    EXPECT_EQ(wb().view("view 2")->shownFrame, 0u); // two frames before the current one
    ASSERT_TRUE(headless.has(wb(), "view.image.view 2"));

    // Orbit the main view: previewed in both (linked) views, one camera.set on release.
    headless.clearEmitted();
    const ui::ItemRect img = headless.rect(wb(), "view.image.main");
    double azimuthWhileHeld = 0, otherWhileHeld = 0;
    headless.drag(wb(), img.cx(), img.cy(), img.cx() + 100, img.cy(), 5, 0, [&] {
        azimuthWhileHeld = wb().view("main")->camera.azimuth;
        otherWhileHeld = wb().view("view 2")->camera.azimuth;
        EXPECT_TRUE(headless.emitted().empty());
    });
    EXPECT_NEAR(azimuthWhileHeld, 330.0, 1e-9); // 100 px at 0.3 degrees each, turning left
    EXPECT_NEAR(otherWhileHeld, 330.0, 1e-9);
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["op"], "camera.set");
    EXPECT_EQ(headless.emitted()[0]["view"], "main");
    EXPECT_NEAR(session.state().view("view 2")->camera.azimuth, 330.0, 1e-9);

    // Wheel zoom: previewed, committed once the wheel rests.
    headless.clearEmitted();
    const double before = wb().view("main")->camera.distance;
    headless.wheel(wb(), img.cx(), img.cy(), 2);
    EXPECT_LT(wb().view("main")->camera.distance, before);
    EXPECT_TRUE(headless.emitted().empty());
    headless.frames(wb(), 40);
    ASSERT_EQ(headless.emitted("camera.set").size(), 1u);
    EXPECT_NEAR(session.state().view("main")->camera.distance, before / (1.15 * 1.15), 1e-9);
}

TEST_F(PanelTest, DraggingABoxFaceInTheViewEmitsOneBoxSet) {
    openLattice();
    session.apply(Json::parse(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[3,3,3]})"));
    wb().selection().box = "b";
    headless.frames(wb(), 3);
    // The +x face handle, where the view draws it.
    const ui::ItemRect img = headless.rect(wb(), "view.image.main");
    const core::CameraState cam = wb().view("main")->camera;
    const ui::ModelBounds mb = ui::modelBounds(*wb().mainDisplay()->frame);
    const double radius = 0.5 * std::sqrt(3.0) * 4.0;
    (void)mb;
    const glm::dvec2 size(img.x1 - img.x0, img.y1 - img.y0);
    const glm::dmat4 vp = ui::projectionMatrix(cam, size.x / size.y, radius) * ui::viewMatrix(cam);
    auto p = ui::projectToPixels(vp, glm::dvec3(3, 1.5, 1.5), size);
    auto q = ui::projectToPixels(vp, glm::dvec3(2.25, 1.5, 1.5), size);
    ASSERT_TRUE(p && q);
    headless.clearEmitted();
    std::size_t visibleWhileHeld = 0;
    headless.drag(wb(), img.x0 + float(p->x), img.y0 + float(p->y), img.x0 + float(q->x),
                  img.y0 + float(q->y), 5, 0, [&] { visibleWhileHeld = visible(); });
    EXPECT_EQ(visibleWhileHeld, 48u); // x in {0, 1, 2}
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["op"], "box.set");
    EXPECT_NEAR(session.state().box("b")->max[0], 2.25, 0.02); // ImGui floors mouse positions
    EXPECT_EQ(session.state().view("main")->camera, core::CameraState{}); // the camera did not move
}

TEST_F(PanelTest, DraggingATabOntoAnEdgeSplitsTheAreaAndUndoRestoresIt) {
    openLattice();
    const ui::ItemRect tab = headless.rect(wb(), "tab.faults");
    const ui::ItemRect img = headless.rect(wb(), "view.image.main");
    headless.drag(wb(), tab.cx(), tab.cy(), img.cx(), img.y1 - 10, 8);
    ASSERT_EQ(headless.emitted("layout.set").size(), 1u);
    const ui::DockNode* area = wb().layout().areaOf("faults");
    ASSERT_NE(area, nullptr);
    EXPECT_EQ(area->tabs, std::vector<std::string>{"faults"});
    EXPECT_NE(wb().layout().areaOf("viewports"), area);
    headless.key(wb(), GLFW_KEY_Z, true);
    headless.frames(wb(), 2);
    EXPECT_EQ(wb().layout().toJson()["root"], ui::DockLayout::defaultLayout().toJson()["root"]);

    // A splitter drag: one layout.set on release, with the new ratio.
    headless.clearEmitted();
    const int rootId = wb().layout().root().id;
    const ui::ItemRect bar = headless.rect(wb(), "splitter." + std::to_string(rootId));
    headless.drag(wb(), bar.cx(), bar.cy(), bar.cx() + 80, bar.cy());
    ASSERT_EQ(headless.emitted("layout.set").size(), 1u);
    EXPECT_GT(session.state().dockLayout["root"]["ratio"].get<double>(), 0.22);
}

TEST_F(PanelTest, TheSessionsLayoutIsAdoptedAndABadOneFallsBack) {
    ui::DockLayout l;
    l.openPanel("viewports");
    session.apply({{"op", "layout.set"}, {"layout", l.toJson()}});
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().layout().contains("viewports"));
    EXPECT_FALSE(wb().layout().contains("faults"));
    session.apply({{"op", "layout.set"}, {"layout", {{"root", {{"split", "sideways"}}}}}});
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().lastMessageIsError());
    EXPECT_TRUE(wb().layout().contains("faults")); // the default layout
}

namespace {
class JournalTest : public PanelTest {
  protected:
    std::string stateDir() override { return dir.file("state"); }
};
} // namespace

TEST_F(JournalTest, EveryCommandIsJournalledAndTheJournalReplays) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kBoxes);
    headless.click(wb(), "boxes.add");
    headless.key(wb(), GLFW_KEY_Z, true);
    const std::string journal = wb().journalPath();
    ASSERT_FALSE(journal.empty());
    std::ifstream in(journal);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line.rfind("//", 0) != 0)
            lines.push_back(line);
    ASSERT_GE(lines.size(), 3u);
    EXPECT_EQ(Json::parse(lines[0])["op"], "data.open");
    EXPECT_EQ(Json::parse(lines[lines.size() - 2])["op"], "box.add");
    EXPECT_EQ(Json::parse(lines.back()), (Json{{"op", "undo"}}));
    core::Session replayed;
    core::ReplayReport report = core::replayJournal(journal, {}, replayed);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(replayed.state().boxes, session.state().boxes);
    // The autosave sits next to the journal.
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(journal).parent_path() /
                                        "recovery.faultline.json"));
}

TEST_F(PanelTest, SessionsOpenInTheBackgroundAsANewHistory) {
    openLattice();
    session.apply(
        Json::parse(R"({"op":"box.add","name":"saved box","min":[0,0,0],"max":[1,1,1]})"));
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    const std::string file = dir.file("a.faultline.json");
    wb().saveSessionAs(file);
    headless.frames(wb(), 2);
    ASSERT_TRUE(std::filesystem::exists(file));
    EXPECT_EQ(wb().sessionPath(), file);
    session.apply(Json::parse(R"({"op":"data.close"})"));
    headless.frames(wb(), 2);
    headless.clearEmitted();
    wb().opener().openSession(file);
    headless.settle(wb());
    EXPECT_EQ(headless.emitted(), (std::vector<Json>{{{"op", "session.open"}, {"path", file}}}));
    ASSERT_NE(session.dataset(), nullptr);
    EXPECT_EQ(session.state().frame, 2u);
    EXPECT_EQ(wb().mainDisplay()->shownFrame, 2u);
    EXPECT_EQ(visible(), 8u);             // the saved keep box [0,1]^3
    headless.key(wb(), GLFW_KEY_Z, true); // issue 41: opening is no undo step
    EXPECT_NE(session.dataset(), nullptr);
    EXPECT_EQ(visible(), 8u);
    EXPECT_EQ(wb().recentFiles().front(), file);
}

// Issue 27: Top / Front / Side fit the visible spheres from their new side, so a zoomed-in view
// is not left cropped until Fit.
TEST_F(PanelTest, PresetViewsFitTheVisibleSpheres) {
    openLattice();
    headless.settle(wb());
    session.apply(
        Json::parse(R"({"op":"camera.set","view":"main","distance":0.5,"target":[9,9,9]})"));
    headless.settle(wb());
    for (const char* preset : {"top", "front", "side"}) {
        SCOPED_TRACE(preset);
        headless.clearEmitted();
        headless.click(wb(), std::string("viewports.preset.") + preset);
        ASSERT_EQ(headless.emitted("camera.set").size(), 1u);
        const Json cmd = headless.emitted("camera.set")[0];
        // The lattice spans 0..3 (radius 0.5): fitted, the target is its centre and the camera
        // stands well back.
        ASSERT_TRUE(cmd.contains("target")) << cmd.dump();
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(cmd["target"][k].get<double>(), 1.5, 0.6);
        EXPECT_GT(cmd["distance"].get<double>(), 3.0);
        headless.settle(wb());
    }
}

namespace faultline::test {
namespace {
// Issue 41, item 8: export dialogs open beside the session (or where the last export went), not
// in the data's folder.
TEST_F(PanelTest, ExportsOpenBesideTheSession) {
    openLattice();
    EXPECT_EQ(wb().exportFolder(), dir.path().string());
    std::filesystem::create_directories(dir.file("analyses"));
    wb().saveSessionAs(dir.file("analyses/a.faultline.json"));
    headless.frames(wb(), 2);
    EXPECT_EQ(wb().exportFolder(), dir.file("analyses"));
}
} // namespace
} // namespace faultline::test
