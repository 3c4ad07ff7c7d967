// The workbench's fault surfaces (Surfaces panel, background builds, meshes sent to the views),
// difference colouring in a view, crash recovery at start, sessions whose data moved, and the
// frame memory budget.
#include "panel_fixture.hpp"

#include "core/model/frame_difference.hpp"
#include "core/session/autosave.hpp"
#include "core/session/color_range.hpp"
#include "core/session/session_json.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/render/mock_renderer.hpp"
#include "ui/viewport/gl_view_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace faultline;
using namespace faultline::test;
using core::Json;

TEST_F(PanelTest, ATickedSurfaceIsBuiltInTheBackgroundAndDrawnWithTheSpheres) {
    ui::GlViewRenderer renderer(ui::RendererBackend::Mock);
    wb().setRenderer(&renderer);
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    headless.clearEmitted();
    headless.click(wb(), "surfaces.show.F1");
    headless.settle(wb()); // the wrapping iso-value is found in the background
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    Json shown = headless.emitted("surface.set")[0];
    // A new surface starts at the iso-value that wraps the fault's spheres (written out, so the
    // journal replays the same surface).
    ASSERT_TRUE(shown.contains("iso")) << shown.dump();
    const double wrapping = shown["iso"].get<double>();
    EXPECT_GT(wrapping, 0.0);
    shown.erase("iso");
    EXPECT_EQ(shown, (Json{{"op", "surface.set"}, {"fault", "F1"}, {"visible", true}}));
    headless.settle(wb());
    const ui::ViewDisplay* d = wb().mainDisplay();
    ASSERT_EQ(d->surfaces.size(), 1u);
    EXPECT_GT(d->surfaces[0].mesh->indices.size(), 0u);
    EXPECT_FLOAT_EQ(d->surfaces[0].opacity, 0.8f);
    const ui::SurfaceStatus st = wb().surfaces().status(session.state(), "F1", d->shownFrame);
    EXPECT_EQ(st.state, ui::SurfaceStatus::State::Ready);
    EXPECT_EQ(st.spheres, 64u);
    auto* mock = dynamic_cast<ui::MockRenderer*>(renderer.rendererOf("main"));
    ASSERT_NE(mock, nullptr);
    EXPECT_EQ(mock->stats().meshTriangles, d->surfaces[0].mesh->indices.size() / 3);

    // Wrap puts a changed iso back to the wrapping one.
    session.apply(Json{{"op", "surface.set"}, {"fault", "F1"}, {"iso", 0.7 * wrapping}});
    headless.settle(wb());
    headless.clearEmitted();
    headless.click(wb(), "surfaces.wrap");
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    EXPECT_DOUBLE_EQ(headless.emitted("surface.set")[0]["iso"].get<double>(), wrapping);
    headless.settle(wb());

    // Another kernel comes with the iso-value that wraps the spheres with it (the compact
    // kernel's field is far smaller than inverse-square's).
    pickFromCombo("surfaces.kernel", "surfaces.kernel.compact");
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    const Json compact = headless.emitted("surface.set")[0];
    EXPECT_EQ(compact.value("kernel", ""), "compact");
    ASSERT_TRUE(compact.contains("iso")) << compact.dump();
    EXPECT_LT(compact["iso"].get<double>(), 0.5 * wrapping);
    EXPECT_EQ(session.state().surface("F1")->kernel, core::MetaballKernel::Compact);
    session.apply(Json::parse(R"({"op":"undo"})"));
    headless.settle(wb());

    // Opacity only: the same mesh, no new build. Undo hides the surface again.
    const std::size_t builds = wb().surfaces().buildsStarted();
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","opacity":0.5})"));
    headless.settle(wb());
    EXPECT_EQ(wb().surfaces().buildsStarted(), builds);
    EXPECT_FLOAT_EQ(wb().mainDisplay()->surfaces[0].opacity, 0.5f);
    // Scrubbing away and back does not rebuild the first frame's surface.
    session.apply(Json::parse(R"({"op":"frame.set","frame":1})"));
    headless.settle(wb());
    session.apply(Json::parse(R"({"op":"frame.set","frame":0})"));
    headless.settle(wb());
    EXPECT_EQ(wb().surfaces().buildsStarted(), builds + 1); // frame 1's, once
    // A hidden fault hides its surface.
    session.apply(Json::parse(R"({"op":"fault.set","name":"F1","visible":false})"));
    headless.settle(wb());
    EXPECT_TRUE(wb().mainDisplay()->surfaces.empty());
    EXPECT_EQ(mock->stats().meshTriangles, 0u);
}

// The Surfaces panel offers the visible spheres' surface even before any fault exists: ticked,
// it starts at the wrapping iso, is built from what the main view shows and follows a threshold.
TEST_F(PanelTest, TheVisibleSpheresSurfaceFollowsTheThresholds) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    // Nothing shown yet: the panel's glTF export is off, as File > Export's is, rather than
    // failing once a file was picked (walkthrough of issue 41).
    headless.click(wb(), "surfaces.export_gltf");
    headless.frames(wb(), 2);
    EXPECT_FALSE(wb().fileDialog().isOpen());
    headless.clearEmitted();
    headless.click(wb(), "surfaces.show.visible");
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    const Json shown = headless.emitted("surface.set")[0];
    EXPECT_EQ(shown.value("fault", ""), "*visible");
    EXPECT_GT(shown.value("iso", 0.0), 0.0) << shown.dump();
    headless.settle(wb());
    const ui::ViewDisplay* d = wb().mainDisplay();
    ASSERT_EQ(d->surfaces.size(), 1u);
    const auto all = d->surfaces[0].mesh;
    auto status = [&] {
        const ui::ViewDisplay* m = wb().mainDisplay();
        return wb().surfaces().status(session.state(), "*visible", m->shownFrame, m->frame,
                                      m->visibility);
    };
    EXPECT_EQ(status().spheres, 64u);
    // Half the spheres visible: a new surface through those.
    session.apply(Json::parse(R"({"op":"threshold.add","variable":"strain","low":0.5,"high":9})"));
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->surfaces.size(), 1u);
    EXPECT_NE(wb().mainDisplay()->surfaces[0].mesh, all);
    EXPECT_EQ(status().spheres, 32u);
    // Its VDB export writes what the op writes, and the journal records it.
    wb().exports().surfaces({"*visible"}, dir.file("out/visible.vdb"), true, false);
    headless.settle(wb());
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/visible.vdb"))) << wb().lastMessage();
    EXPECT_EQ(session.journal().back().value("fault", ""), "*visible");
}

// Figure 4 in the panel: colour a surface by a variable, or like the main view in one click; the
// mesh's vertex colours follow (strain = x / 3 on the lattice).
TEST_F(PanelTest, ASurfaceIsColouredByAVariableOrLikeTheView) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(
        R"({"op":"surface.set","fault":"F1","kernel":"compact","iso":0.5,"color_reach":1})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    headless.settle(wb());
    pickFromCombo("surfaces.color_by", "surfaces.color_by.strain");
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    EXPECT_EQ(
        headless.emitted("surface.set")[0],
        (Json{{"op", "surface.set"}, {"fault", "F1"}, {"color_by", "strain"}, {"range", nullptr}}));
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->surfaces.size(), 1u);
    const auto& mesh = *wb().mainDisplay()->surfaces[0].mesh;
    auto spread = [](const ui::MeshData& m) {
        float lo = 1, hi = 0;
        for (std::size_t k = 0; k < m.colors.size(); k += 3) {
            lo = std::min(lo, m.colors[k + 1]);
            hi = std::max(hi, m.colors[k + 1]);
        }
        return hi - lo;
    };
    EXPECT_GT(spread(mesh), 0.3f); // viridis over the strain range: far from one colour
    // Like the view: the main view's variable, map and range.
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","variable":"layer","map":"gray"})"));
    headless.settle(wb());
    headless.clearEmitted();
    headless.click(wb(), "surfaces.like_view");
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    const Json like = headless.emitted("surface.set")[0];
    EXPECT_EQ(like.value("color_by", ""), "layer");
    EXPECT_EQ(like.value("map", ""), "gray");
    ASSERT_TRUE(like.contains("range")) << like.dump();
    EXPECT_EQ(like["range"],
              Json::array({wb().mainDisplay()->colorRange[0], wb().mainDisplay()->colorRange[1]}));
    EXPECT_EQ(session.state().surface("F1")->colorBy, "layer");
}

// Strains derived again under the same names (another reference or cutoff) may give a surface
// coloured by them other colours: the workbench builds it again instead of drawing the colours of
// the old values. (The lattice does not move, so here the values happen to stay zero; the store
// keys by how they were derived, not by looking at them.)
TEST_F(PanelTest, ASurfaceColouredByStrainIsBuiltAgainWhenTheStrainIsDerivedAgain) {
    openLattice();
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    session.apply(Json::parse(R"({"op":"strain.add","since_offset":-1,"prefix":"inc_"})"));
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","kernel":"compact","iso":0.5,)"
                              R"("color_reach":1,"color_by":"inc_shear_strain"})"));
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->surfaces.size(), 1u);
    const auto before = wb().mainDisplay()->surfaces[0].mesh;
    session.apply(Json::parse(R"({"op":"strain.remove","prefix":"inc_"})"));
    session.apply(
        Json::parse(R"({"op":"strain.add","since_frame":0,"cutoff":2.5,"prefix":"inc_"})"));
    headless.settle(wb());
    ASSERT_EQ(wb().mainDisplay()->surfaces.size(), 1u);
    EXPECT_NE(wb().mainDisplay()->surfaces[0].mesh, before);
    // Colouring by a variable read from the file keeps the surface across such a change.
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","color_by":"strain"})"));
    headless.settle(wb());
    const auto byRead = wb().mainDisplay()->surfaces[0].mesh;
    session.apply(Json::parse(R"({"op":"strain.remove","prefix":"inc_"})"));
    session.apply(Json::parse(R"({"op":"strain.add","since_offset":-1,"prefix":"inc_"})"));
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->surfaces[0].mesh, byRead);
}

// Issue 41: "own colour" in the colour menu gives the surface a colour apart from its fault's
// (the fault's complement to start with), shown in the views and in the surfaces' list; "fault
// colour" takes it back.
TEST_F(PanelTest, ASurfaceTakesAColourOfItsOwnFromThePanel) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(R"({"op":"fault.set","name":"F1","color":[1,0.5,0]})"));
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","kernel":"compact","iso":0.5})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    headless.settle(wb());
    pickFromCombo("surfaces.color_by", "surfaces.color_by.own");
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    EXPECT_EQ(
        headless.emitted("surface.set")[0],
        (Json{
            {"op", "surface.set"}, {"fault", "F1"}, {"color_by", ""}, {"color", {0.0, 0.5, 1.0}}}));
    headless.settle(wb());
    EXPECT_TRUE(headless.has(wb(), "surfaces.colour"));
    ASSERT_EQ(wb().mainDisplay()->surfaces.size(), 1u);
    const auto& mesh = *wb().mainDisplay()->surfaces[0].mesh;
    ASSERT_FALSE(mesh.colors.empty());
    EXPECT_NEAR(mesh.colors[0], 0.0f, 1e-3f);
    EXPECT_NEAR(mesh.colors[1], 0.5f, 1e-3f);
    EXPECT_NEAR(mesh.colors[2], 1.0f, 1e-3f);
    headless.clearEmitted();
    pickFromCombo("surfaces.color_by", "surfaces.color_by.plain");
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    EXPECT_EQ(headless.emitted("surface.set")[0],
              (Json{{"op", "surface.set"}, {"fault", "F1"}, {"color_by", ""}, {"color", nullptr}}));
    EXPECT_FALSE(session.state().surface("F1")->color.has_value());
}

TEST_F(PanelTest, SurfaceSettingsAreCommandsAndABadRequestSaysWhy) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","voxel":1e-6})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    headless.settle(wb());
    const ui::SurfaceStatus st = wb().surfaces().status(session.state(), "F1", 0);
    EXPECT_EQ(st.state, ui::SurfaceStatus::State::Failed);
    EXPECT_NE(st.error.find("voxel size"), std::string::npos) << st.error;
    EXPECT_TRUE(wb().mainDisplay()->surfaces.empty());
}

TEST_F(PanelTest, AViewColoursByTheChangeSinceAFrame) {
    openLattice();
    // strain = x/3 + frame: at frame 2 every sphere's strain rose by 2 since frame 0.
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    session.apply(Json::parse(
        R"({"op":"color.set","view":"main","variable":"strain","difference":"change","since_frame":0})"));
    headless.settle(wb());
    const ui::ViewDisplay* d = wb().mainDisplay();
    ASSERT_NE(d->colorColumn, nullptr);
    EXPECT_EQ(d->colorTitle, "strain change since frame 0");
    ASSERT_EQ(d->colorColumn->floats.size(), 64u);
    for (float v : d->colorColumn->floats)
        EXPECT_NEAR(v, 2.0f, 1e-5f);
    // Relative: one frame back.
    session.apply(Json::parse(R"({"op":"color.set","view":"main","since_offset":-1})"));
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorTitle, "strain change since frame 1");
    EXPECT_NEAR(wb().mainDisplay()->colorColumn->floats[5], 1.0f, 1e-5f);
    // Displacement: the lattice does not move.
    session.apply(Json::parse(R"({"op":"color.set","view":"main","difference":"displacement"})"));
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorTitle, "displacement since frame 1");
    EXPECT_EQ(wb().mainDisplay()->colorColumn->max, 0.0);
    // Undo twice: back to the change since frame 0.
    session.undo();
    session.undo();
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorTitle, "strain change since frame 0");
}

// Issue 41: the live view's range over "all frames" was the frames seen so far (a change since
// frame 0 shown only at frame 0 spanned nothing) while figures took every frame; the legends
// differed until every frame had been visited. The view now takes the range over every frame,
// worked out in the background, as figures do.
TEST_F(PanelTest, TheLiveRangeOverAllFramesIsTheFiguresRange) {
    openLattice();
    session.apply(Json::parse(
        R"({"op":"color.set","view":"main","variable":"strain","difference":"change","since_frame":0})"));
    headless.settle(wb());
    const auto figure = core::colorRangeOverFrames(*session.dataset(), session.state().views[0]);
    ASSERT_TRUE(figure.has_value());
    EXPECT_GT(figure->high, 1.0); // strain rises by one a frame
    EXPECT_EQ(wb().mainDisplay()->colorRange[0], figure->low);
    EXPECT_EQ(wb().mainDisplay()->colorRange[1], figure->high);
    // A plain variable under "all frames": the same, before the other frames were shown.
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","difference":"none","range_mode":"all"})"));
    headless.settle(wb());
    const auto plain = core::colorRangeOverFrames(*session.dataset(), session.state().views[0]);
    ASSERT_TRUE(plain.has_value());
    EXPECT_EQ(wb().mainDisplay()->colorRange[0], plain->low);
    EXPECT_EQ(wb().mainDisplay()->colorRange[1], plain->high);
}

// Issue 41, item 9: in the colour popup, Enter in the "since" frame field applies (even the
// number shown), and applying closes the popup.
TEST_F(PanelTest, EnterInTheSinceFieldAppliesAndClosesThePopup) {
    openLattice();
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    session.apply(Json::parse(
        R"({"op":"color.set","view":"main","variable":"strain","difference":"change","since_frame":0})"));
    headless.settle(wb());
    headless.click(wb(), "view.colour.main");
    headless.frames(wb(), 2);
    ASSERT_TRUE(headless.has(wb(), "view.since.main"));
    headless.clearEmitted();
    headless.retype(wb(), "view.since.main", "1");
    headless.frames(wb(), 2);
    ASSERT_EQ(headless.emitted("color.set").size(), 1u);
    EXPECT_EQ(headless.emitted("color.set")[0],
              (Json{{"op", "color.set"}, {"view", "main"}, {"since_frame", 1}}));
    EXPECT_FALSE(headless.has(wb(), "view.since.main")) << "the popup stays open";
    // Enter on the number already shown applies too.
    headless.click(wb(), "view.colour.main");
    headless.frames(wb(), 2);
    headless.clearEmitted();
    headless.retype(wb(), "view.since.main", "1");
    headless.frames(wb(), 2);
    EXPECT_EQ(headless.emitted("color.set").size(), 1u);
}

// Walkthrough of issue 41: with a change shown, picking "this frame's min to max" changed
// nothing (a change is coloured over all frames, so colours mean the same at every frame).
// The choice is now off there, and "all frames" reads as chosen; a plain variable keeps all
// three.
TEST_F(PanelTest, AChangeColouringOffersNoPerFrameRange) {
    openLattice();
    session.apply(Json::parse(
        R"({"op":"color.set","view":"main","variable":"strain","difference":"change","since_frame":0})"));
    ASSERT_EQ(session.state().views[0].rangeMode, core::RangeMode::CurrentFrame);
    headless.settle(wb());
    headless.click(wb(), "view.colour.main");
    headless.frames(wb(), 2);
    ASSERT_TRUE(headless.has(wb(), "view.range.frame.main"));
    clickInColourPopup("view.range.frame.main");
    headless.click(wb(), "view.range.all.main"); // already what is shown
    headless.frames(wb(), 2);
    EXPECT_TRUE(headless.emitted("color.set").empty());
    // The value itself: "this frame's" is there again.
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","difference":"none","range_mode":"all"})"));
    headless.settle(wb());
    clickInColourPopup("view.range.frame.main");
    ASSERT_EQ(headless.emitted("color.set").size(), 1u);
    EXPECT_EQ(headless.emitted("color.set")[0]["range_mode"], "frame");
}

// Second walkthrough of issue 41: after choosing a change colouring in the colour popup, its
// range fields still showed the value's range (0.0004 / 5.2278 against +-3.77) until applied,
// so typing one end sent the other stale. They follow the range shown.
TEST_F(PanelTest, TheRangeFieldsFollowTheRangeShown) {
    openLattice();
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"strain"})"));
    headless.settle(wb());
    headless.click(wb(), "view.colour.main");
    headless.frames(wb(), 2);
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","difference":"change","since_frame":0})"));
    headless.settle(wb());
    ASSERT_TRUE(headless.has(wb(), "view.range.high.main")) << "the popup stays open";
    const double low = wb().mainDisplay()->colorRange[0];
    EXPECT_EQ(low, -2.0); // the lattice's strain rises by one a frame, over three frames
    headless.clearEmitted();
    headless.retype(wb(), "view.range.high.main", "3");
    headless.frames(wb(), 2);
    ASSERT_EQ(headless.emitted("color.set").size(), 1u);
    EXPECT_EQ(headless.emitted("color.set")[0]["range"], Json::array({low, 3.0}));
}

// "1st to 99th percentile" in the colour popup: a fixed range over the spheres shown without
// their extremes, through color.set; off for a change colouring.
TEST_F(PanelTest, ThePercentileRangeLeavesTheExtremesOut) {
    openLattice();
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"x"})"));
    headless.settle(wb());
    const auto* d = wb().mainDisplay();
    ASSERT_TRUE(d && d->frame && d->visibility);
    const auto expected = core::maskedQuantiles(*d->frame, "x", d->visibility->mask, 0.01, 0.99);
    ASSERT_TRUE(expected && expected->first < expected->second);
    headless.click(wb(), "view.colour.main");
    headless.frames(wb(), 2);
    ASSERT_TRUE(headless.has(wb(), "view.range.fix_percentile.main"));
    clickInColourPopup("view.range.fix_percentile.main");
    ASSERT_EQ(headless.emitted("color.set").size(), 1u);
    EXPECT_EQ(headless.emitted("color.set")[0]["range_mode"], "fixed");
    EXPECT_EQ(headless.emitted("color.set")[0]["range"],
              Json::array({expected->first, expected->second}));
    EXPECT_EQ(session.state().views[0].rangeMode, core::RangeMode::Fixed);
    // The "percentile" mode: the same range, following the frame and the spheres shown.
    clickInColourPopup("view.range.percentile.main");
    ASSERT_EQ(headless.emitted("color.set").size(), 1u);
    EXPECT_EQ(headless.emitted("color.set")[0],
              Json::parse(R"({"op":"color.set","view":"main","range_mode":"percentile"})"));
    EXPECT_EQ(session.state().views[0].rangeMode, core::RangeMode::Percentile);
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorRange[0], expected->first);
    EXPECT_EQ(wb().mainDisplay()->colorRange[1], expected->second);
    // A change colouring: the button and the mode are there but off.
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","difference":"change","since_frame":0})"));
    headless.settle(wb());
    clickInColourPopup("view.range.fix_percentile.main");
    EXPECT_TRUE(headless.emitted("color.set").empty());
    clickInColourPopup("view.range.percentile.main");
    EXPECT_TRUE(headless.emitted("color.set").empty());
}

namespace {
class RecoveryTest : public PanelTest {
  protected:
    std::string stateDir() override { return dir.file("state"); }
    void SetUp() override {
        // A run that crashed: its autosave has a box and no clean exit.
        core::Session crashed;
        crashed.apply({{"op", "data.open"}, {"paths", {writeLattice(dir.file("lattice.dump"))}}});
        crashed.apply(
            Json::parse(R"({"op":"box.add","name":"unsaved work","min":[0,0,0],"max":[1,1,1]})"));
        core::Autosave(stateDir()).saveNow(crashed, false);
        PanelTest::SetUp();
    }
};
} // namespace

TEST_F(RecoveryTest, TheNextStartOffersTheCrashedSessionAndRecoversIt) {
    ASSERT_TRUE(wb().pendingRecovery().has_value());
    headless.frames(wb(), 2);
    headless.click(wb(), "recovery.recover");
    headless.settle(wb());
    EXPECT_FALSE(wb().pendingRecovery().has_value());
    ASSERT_NE(session.state().box("unsaved work"), nullptr);
    ASSERT_NE(session.dataset(), nullptr);
    EXPECT_TRUE(wb().sessionPath().empty())
        << "saving must ask where, not overwrite the recovery file";
    // From now on the autosave holds this run's session (the recovered one).
    headless.frames(wb(), 2);
    EXPECT_NE(core::loadSessionFile(core::Autosave(stateDir()).sessionPath()).box("unsaved work"),
              nullptr);
}

TEST_F(RecoveryTest, DiscardingKeepsNothingToOffer) {
    headless.frames(wb(), 2);
    headless.click(wb(), "recovery.discard");
    EXPECT_FALSE(wb().pendingRecovery().has_value());
    EXPECT_EQ(session.state().box("unsaved work"), nullptr);
    // The autosave holds this run's session now, without the discarded work.
    session.apply(Json::parse(R"({"op":"box.add","name":"new","min":[0,0,0],"max":[1,1,1]})"));
    headless.frames(wb(), 2);
    const core::SessionState saved =
        core::loadSessionFile(core::Autosave(stateDir()).sessionPath());
    EXPECT_EQ(saved.box("unsaved work"), nullptr);
    EXPECT_NE(saved.box("new"), nullptr);
}

TEST_F(PanelTest, ASessionWhoseDataMovedAsksWhereItWent) {
    openLattice();
    session.apply(Json::parse(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,1,1]})"));
    const std::string file = dir.file("s.faultline.json");
    core::saveSessionFile(session.state(), file);
    session.apply(Json::parse(R"({"op":"data.close"})"));
    std::filesystem::create_directories(dir.file("moved"));
    std::filesystem::rename(dir.file("lattice.dump"), dir.file("moved/lattice.dump"));
    headless.frames(wb(), 2);
    wb().opener().openSession(file);
    headless.settle(wb());
    ASSERT_TRUE(wb().opener().missingData().has_value());
    EXPECT_EQ(wb().opener().missingData()->paths.front(), dir.file("lattice.dump"));
    EXPECT_EQ(session.dataset(), nullptr);
    headless.clearEmitted();
    wb().opener().relocate(dir.file("moved/lattice.dump"));
    headless.settle(wb());
    EXPECT_FALSE(wb().opener().missingData().has_value());
    ASSERT_NE(session.dataset(), nullptr);
    EXPECT_EQ(session.state().dataPaths.front(), dir.file("moved/lattice.dump"));
    ASSERT_NE(session.state().box("b"), nullptr);
    ASSERT_EQ(headless.emitted("session.open").size(), 1u);
    EXPECT_EQ(headless.emitted("session.open")[0]["data"],
              Json::array({dir.file("moved/lattice.dump")}));
}

TEST(WorkbenchAutosave, ACleanExitLeavesNothingToRecoverAndACrashDoes) {
    TempDir dir;
    HeadlessUi headless;
    core::Session session;
    ui::WorkbenchOptions options;
    options.stateDir = dir.file("state");
    options.autosaveSeconds = 0;
    {
        ui::Workbench wb(session, options);
        session.apply(Json::parse(R"({"op":"view.add","name":"second"})"));
        headless.frames(wb, 2);
        // Running: the autosave is there and would be offered after a crash.
        EXPECT_TRUE(core::Autosave(options.stateDir).pending().has_value());
    }
    EXPECT_FALSE(core::Autosave(options.stateDir).pending().has_value());
}

TEST_F(PanelTest, TheFrameMemoryBudgetIsASettingAppliedToTheData) {
    openLattice();
    EXPECT_EQ(session.dataset()->cacheBudget(), core::defaultFrameMemoryBudget());
    wb().setFrameMemoryBudget(std::size_t{256} << 20);
    EXPECT_EQ(session.dataset()->cacheBudget(), std::size_t{256} << 20);
    // Data opened later gets it too.
    session.apply(Json::parse(R"({"op":"data.close"})"));
    wb().opener().openData({dir.file("lattice.dump")});
    headless.settle(wb());
    ASSERT_NE(session.dataset(), nullptr);
    EXPECT_EQ(session.dataset()->cacheBudget(), std::size_t{256} << 20);
    wb().setFrameMemoryBudget(0);
    EXPECT_EQ(session.dataset()->cacheBudget(), core::defaultFrameMemoryBudget());
}

TEST_F(PanelTest, FitVisibleAimsAtTheVisibleSpheresAndContextModeIsAViewSetting) {
    openLattice();
    session.apply(Json::parse(R"({"op":"box.add","name":"corner","min":[0,0,0],"max":[1,1,1]})"));
    headless.showPanel(wb(), ui::panel_ids::kViewports);
    headless.clearEmitted();
    headless.click(wb(), "viewports.fit_visible");
    const auto cams = headless.emitted("camera.set");
    ASSERT_EQ(cams.size(), 1u);
    // The visible spheres are centres 0..1 with radius 0.5: the box [-0.5, 1.5]^3.
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(cams[0]["target"][a].get<double>(), 0.5,
                    0.3); // shifted sideways for the legend only
    const double full =
        wb().fitCamera(*session.state().view("main"), session.state().view("main")->camera,
                       {-0.5, -0.5, -0.5}, {3.5, 3.5, 3.5})
            .distance;
    EXPECT_LT(cams[0]["distance"].get<double>(), 0.6 * full);
    headless.click(wb(), "viewports.context");
    ASSERT_EQ(headless.emitted("view.set").size(), 1u);
    EXPECT_TRUE(session.state().view("main")->contextPoints);
}

TEST_F(PanelTest, SurfacesExportInTheBackgroundAndTheJournalRecordsIt) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","kernel":"compact"})"));
    wb().exports().surfaces({"F1"}, dir.file("out/F1.vdb"), true, false);
    wb().exports().surfaces({"F1"}, dir.file("out/faults.glb"), false, false);
    headless.settle(wb());
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/F1.vdb"))) << wb().lastMessage();
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/faults.glb"))) << wb().lastMessage();
    // With the spheres as glyphs: a larger file, and the journal says so.
    wb().exports().surfaces({"F1"}, dir.file("out/glyphs.glb"), false, true);
    headless.settle(wb());
    EXPECT_GT(std::filesystem::file_size(dir.file("out/glyphs.glb")),
              std::filesystem::file_size(dir.file("out/faults.glb")));
    EXPECT_EQ(session.journal().back().value("glyphs", false), true);
    std::vector<std::string> ops;
    for (const auto& c : session.journal())
        ops.push_back(c.value("op", ""));
    EXPECT_NE(std::find(ops.begin(), ops.end(), "export.vdb"), ops.end());
    EXPECT_NE(std::find(ops.begin(), ops.end(), "export.gltf"), ops.end());
    // A fault that cannot be built says why, and records nothing.
    session.apply(Json::parse(R"({"op":"surface.set","fault":"F1","voxel":1e-6})"));
    const std::size_t before = session.journal().size();
    wb().exports().surfaces({"F1"}, dir.file("out/bad.vdb"), true, false);
    headless.settle(wb());
    EXPECT_TRUE(wb().lastMessageIsError());
    EXPECT_NE(wb().lastMessage().find("F1"), std::string::npos) << wb().lastMessage();
    EXPECT_EQ(session.journal().size(), before);
}

// Tracks and metrics read every frame: the workbench writes them on a worker thread (the UI keeps
// drawing), records the export.csv when the file is written, and writes what the op writes.
TEST_F(PanelTest, CsvExportsOfEveryFrameRunInTheBackgroundAndMatchTheOp) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    for (const char* what : {"fault_tracks", "fault_metrics"}) {
        const std::string mine = dir.file(std::string("out/") + what + ".csv");
        const std::string ops = dir.file(std::string("out/") + what + "-op.csv");
        wb().exports().csv({{"op", "export.csv"}, {"what", what}, {"path", mine}});
        EXPECT_TRUE(wb().jobs().busy() || std::filesystem::exists(mine));
        headless.settle(wb());
        ASSERT_TRUE(std::filesystem::exists(mine)) << wb().lastMessage();
        EXPECT_EQ(session.journal().back().value("op", ""), "export.csv");
        EXPECT_EQ(session.journal().back().value("what", ""), what);
        session.apply(Json{{"op", "export.csv"}, {"what", what}, {"path", ops}});
        std::ifstream a(mine), b(ops);
        const std::string ta((std::istreambuf_iterator<char>(a)), {}),
            tb((std::istreambuf_iterator<char>(b)), {});
        EXPECT_FALSE(ta.empty());
        EXPECT_EQ(ta, tb) << what;
    }
    // The frame changes while an export runs: the journal has the export first (it read the
    // frame before), so a replay writes the same file.
    wb().exports().surfaces({"F1"}, dir.file("out/late.vdb"), true, false);
    session.apply(Json{{"op", "frame.set"}, {"frame", 1}});
    headless.settle(wb());
    ASSERT_TRUE(std::filesystem::exists(dir.file("out/late.vdb"))) << wb().lastMessage();
    ASSERT_GE(session.journal().size(), 2u);
    EXPECT_EQ(session.journal()[session.journal().size() - 2].value("op", ""), "export.vdb");
    EXPECT_EQ(session.journal().back().value("op", ""), "frame.set");
    // A bad request says why and records nothing.
    const std::size_t before = session.journal().size();
    wb().exports().csv(
        {{"op", "export.csv"}, {"what", "nonsense"}, {"path", dir.file("out/x.csv")}});
    headless.settle(wb());
    EXPECT_TRUE(wb().lastMessageIsError());
    EXPECT_NE(wb().lastMessage().find("what"), std::string::npos) << wb().lastMessage();
    EXPECT_EQ(session.journal().size(), before);
}

// Issue 27: the Surfaces panel's settings follow the surface just ticked and the fault picked in
// the Faults panel, so Wrap and the other settings act on the surface the user is looking at.
TEST_F(PanelTest, SurfaceSettingsFollowTheTickedSurfaceAndThePickedFault) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"A","ids":[1,2,3,4,5,6,7,8]})"));
    session.apply(Json::parse(R"({"op":"fault.create","name":"B","ids":[60,61,62,63,64]})"));
    session.apply(Json::parse(R"({"op":"surface.set","fault":"A","kernel":"compact","iso":0.1})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    headless.settle(wb());
    auto settingsFault = [&] {
        headless.settle(wb());
        headless.clearEmitted();
        headless.click(wb(), "surfaces.wrap"); // acts on the surface whose settings show
        headless.settle(wb());
        const auto sets = headless.emitted("surface.set");
        return sets.empty() ? std::string("(none)") : sets.back()["fault"].get<std::string>();
    };
    EXPECT_EQ(settingsFault(), "A");
    headless.click(wb(), "surfaces.show.B"); // ticked: B's settings show
    headless.settle(wb());
    EXPECT_EQ(settingsFault(), "B");
    wb().selection().faults = {"A"}; // picked in the Faults panel
    headless.settle(wb());
    EXPECT_EQ(settingsFault(), "A");
}

// Issue 27: an empty surface says why (the iso above the field's maximum) and offers Wrap.
TEST_F(PanelTest, AnEmptySurfaceSaysWhyAndOffersWrap) {
    openLattice();
    session.apply(Json::parse(R"({"op":"fault.create","name":"A","ids":[1,2,3,4,5,6,7,8]})"));
    session.apply(Json::parse(
        R"({"op":"surface.set","fault":"A","kernel":"compact","iso":50,"visible":true})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    wb().selection().faults = {"A"};
    headless.settle(wb());
    const ui::SurfaceStatus st =
        wb().surfaces().status(session.state(), "A", wb().mainDisplay()->shownFrame);
    ASSERT_EQ(st.state, ui::SurfaceStatus::State::Ready) << st.error;
    EXPECT_EQ(st.triangles, 0u);
    EXPECT_LT(st.fieldMax, 50.0f);
    EXPECT_GT(st.fieldMax, 0.0f);
    ASSERT_TRUE(headless.has(wb(), "surfaces.empty_wrap"));
    headless.clearEmitted();
    headless.click(wb(), "surfaces.empty_wrap");
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("surface.set").size(), 1u);
    EXPECT_LT(headless.emitted("surface.set")[0]["iso"].get<double>(), 50.0);
    headless.settle(wb());
    EXPECT_GT(
        wb().surfaces().status(session.state(), "A", wb().mainDisplay()->shownFrame).triangles, 0u);
}

// Issue 27: the iso slider spans the iso-values worth trying for this fault (from the built
// field), so a drag to either end still shows a surface; the value stands beside the slider in
// its own field, which takes typing after one click.
TEST_F(PanelTest, IsoSliderSpansTheFieldsUsefulRangeAndTheValueTakesTyping) {
    openLattice();
    session.apply(Json::parse(
        R"({"op":"fault.create","name":"A","ids":[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16]})"));
    session.apply(
        Json::parse(R"({"op":"surface.set","fault":"A","kernel":"inverse","visible":true})"));
    headless.showPanel(wb(), ui::panel_ids::kSurfaces);
    wb().selection().faults = {"A"};
    headless.settle(wb());
    auto status = [&] {
        return wb().surfaces().status(session.state(), "A", wb().mainDisplay()->shownFrame);
    };
    const ui::SurfaceStatus st = status();
    ASSERT_EQ(st.state, ui::SurfaceStatus::State::Ready) << st.error;
    ASSERT_GT(st.triangles, 0u);
    EXPECT_GT(st.isoLow, 0.0f);
    EXPECT_GT(st.isoHigh, 2 * st.isoLow);
    EXPECT_GT(st.isoHigh, st.iso);
    const float left = std::min(st.isoLow, st.iso); // the range always holds the setting
    // Both ends of the slider give a surface.
    for (const float end : {0.0f, 1.0f}) {
        const ui::ItemRect r = headless.rect(wb(), "surfaces.iso");
        headless.clearEmitted();
        const float x = r.x0 + 2 + end * (r.x1 - r.x0 - 4);
        headless.drag(wb(), r.cx(), r.cy(), x, r.cy());
        headless.settle(wb());
        const auto sets = headless.emitted("surface.set");
        ASSERT_EQ(sets.size(), 1u);
        const double iso = sets[0]["iso"].get<double>();
        EXPECT_NEAR(iso, end == 0.0f ? left : st.isoHigh, 0.02 * iso);
        headless.settle(wb());
        EXPECT_GT(status().triangles, 0u) << "iso " << iso;
    }
    // One click on the value, type, Enter: one surface.set with the typed value.
    headless.clearEmitted();
    headless.retype(wb(), "surfaces.iso_value", "2.5", GLFW_KEY_ENTER);
    headless.settle(wb());
    const auto typed = headless.emitted("surface.set");
    ASSERT_EQ(typed.size(), 1u);
    EXPECT_DOUBLE_EQ(typed[0]["iso"].get<double>(), 2.5);
    // Escape cancels: nothing is emitted and the field shows the setting again.
    headless.clearEmitted();
    headless.retype(wb(), "surfaces.iso_value", "7", GLFW_KEY_ESCAPE);
    headless.settle(wb());
    EXPECT_TRUE(headless.emitted("surface.set").empty());
}
