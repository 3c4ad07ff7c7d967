// Typed command builders (core/session/commands.hpp, issue 39): each builder's command is what
// its op accepts. The commands run in sequence on a session with the lattice open, so a field
// the op does not know, a wrong type or a wrong enum name fails here.
#include "core/session/command_label.hpp"
#include "core/session/commands.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "lattice_dump.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;
using faultline::test::TempDir;

namespace {

void run(Session& s, const Json& command) {
    SCOPED_TRACE(command.dump());
    EXPECT_NO_THROW(s.apply(command));
}

} // namespace

TEST(Commands, EachBuilderMakesACommandItsOpAccepts) {
    TempDir dir;
    Session s;
    const std::string data = dir.write("lattice.dump", faultline::test::latticeDump());
    run(s, cmd::dataOpen({data}));
    run(s, cmd::frameSet(2));

    run(s, cmd::boxAdd("b", {0, 0, 0}, {3, 3, 1}, BoxMode::Keep));
    run(s, cmd::BoxSet("b").enabled(false).mode(BoxMode::Cut).min({0, 0, 0}).max({2, 2, 2}));
    run(s, cmd::BoxSet("b").rename("c"));
    EXPECT_NE(s.state().box("c"), nullptr);
    EXPECT_EQ(s.state().box("c")->mode, BoxMode::Cut);
    CuttingBox copy = *s.state().box("c");
    copy.name = "d";
    run(s, cmd::boxAdd(copy));
    EXPECT_EQ(s.state().box("d")->mode, BoxMode::Cut);
    run(s, cmd::boxRemove("d"));
    run(s, cmd::boxRemove("c"));

    run(s, cmd::ThresholdAdd("strain").low(2.1).high(4));
    run(s, cmd::ThresholdSet("strain").enabled(false).low(2).high(3));
    run(s, cmd::thresholdRemove("strain"));
    run(s, cmd::ThresholdAdd("layer"));

    run(s, cmd::ViewAdd("v2").offset(-1));
    run(s, cmd::ViewSet("v2").frame(0));
    run(s, cmd::ViewSet("v2").offset(-2).linkedCamera(false).contextPoints(true));
    run(s, cmd::CameraSet("main").distance(10).azimuth(30).elevation(20).target({1, 1, 1}));
    run(s, cmd::CameraSet("v2").orthographic(true));
    CameraState camera;
    camera.distance = 7;
    camera.azimuth = -45;
    run(s, cmd::CameraSet("main").all(camera));
    EXPECT_EQ(s.state().view("main")->camera.distance, 7);
    run(s, cmd::ColorSet("main").variable("strain").map("viridis").rangeMode(RangeMode::AllFrames));
    run(s, cmd::ColorSet("main").range(0, 3));
    EXPECT_EQ(s.state().view("main")->rangeMode, RangeMode::Fixed);
    run(s, cmd::ColorSet("main").difference(ColorDifference::Mode::Change).sinceFrame(0));
    run(s, cmd::ColorSet("main").sinceOffset(-1));
    run(s, cmd::ColorSet("v2").difference(ColorDifference::Mode::Displacement));
    run(s, cmd::ColorSet("v2").variable("").difference(ColorDifference::Mode::None));
    run(s, cmd::viewRemove("v2"));

    run(s, cmd::StrainAdd().sinceOffset(-1).cutoff(1.5).prefix("inc_"));
    run(s, cmd::StrainAdd().sinceFrame(0));
    run(s, cmd::strainRemove("inc_"));

    run(s, cmd::FaultCreate("F1", {1, 2, 3, 4}).color({0.2f, 0.4f, 0.6f}).notes("planted"));
    run(s, cmd::faultAdd("F1", {5, 6}));
    run(s, cmd::faultRemove("F1", {6}));
    run(s, cmd::faultAddVisible("F1"));
    run(s, cmd::FaultSet("F1").visible(false).color({1, 0, 0}).notes("n").rename("F2"));
    run(s, cmd::FaultCreate("F3", {40, 41}));
    run(s, cmd::faultCreateVisible("V"));
    EXPECT_EQ(s.state().fault("V")->ids.size(), s.visibility().visibleCount);
    run(s, cmd::faultDelete("V"));
    run(s, cmd::faultMerge({"F2", "F3"}, "F2"));
    run(s, cmd::faultFilter({FaultFilter::Mode::Only, "F2"}));
    run(s, cmd::faultFilter({FaultFilter::Mode::Labelled, {}}));
    run(s, cmd::faultFilter({FaultFilter::Mode::All, {}}));
    run(s, cmd::FaultCandidates().link(1.5).minSize(4).prefix("K").angle(30));
    run(s, cmd::FaultCandidates().method(CandidateMethod::Connected).prefix("L"));

    run(s, cmd::SurfaceSet("F2").visible(true).iso(0.5).opacity(0.8).voxel(0.25).kernel(
               MetaballKernel::InverseSquare));
    run(s, cmd::SurfaceSet("F2").colorBy("").color(std::array<double, 3>{0.1, 0.2, 0.3}));
    run(s, cmd::SurfaceSet("F2").color(std::nullopt).colorBy("strain").clearRange());
    run(s, cmd::SurfaceSet("F2").colorReach(1.0));
    run(s, cmd::SurfaceSet("F2").colorReach(std::nullopt));
    run(s, cmd::exportCsv("faults", dir.file("faults.csv")));
    run(s, cmd::exportVdb("F2", dir.file("f2.vdb")));
    run(s, cmd::exportGltf({"F2"}, dir.file("f2.glb"), true));
    run(s, cmd::surfaceRemove("F2"));
    std::vector<std::int64_t> walls; // the lattice's x = 0 and x = 3 walls: two pieces
    for (std::int64_t id = 1; id <= 64; ++id)
        if ((id - 1) % 4 == 0 || (id - 1) % 4 == 3)
            walls.push_back(id);
    run(s, cmd::FaultCreate("W", walls));
    run(s, cmd::faultSplit("W"));
    run(s, cmd::faultDelete("W.1"));
    EXPECT_NE(s.state().fault("W.2"), nullptr);

    run(s, cmd::layoutSet(Json::object({{"panels", Json::object()}})));
    run(s, cmd::batch({cmd::frameSet(0), cmd::frameSet(1)}));
    EXPECT_EQ(s.state().frame, 1u);
    EXPECT_EQ(cmd::batch({cmd::frameSet(2)}), cmd::frameSet(2)); // one command: itself
    run(s, cmd::undo());
    run(s, cmd::redo());

    const std::string saved = dir.file("s.faultline.json");
    run(s, cmd::sessionSave(saved));
    Session other;
    run(other, cmd::sessionOpen(saved));
    EXPECT_EQ(sessionToJson(other.state(), "").dump(), sessionToJson(s.state(), "").dump());
    Session moved;
    run(moved, cmd::sessionOpen(saved, {data}));
    run(moved, cmd::dataClose());
}

TEST(Commands, BuildersWriteTheJournalsNames) {
    EXPECT_EQ(Json(cmd::BoxSet("b").mode(BoxMode::Keep)),
              Json::parse(R"({"op":"box.set","name":"b","mode":"keep"})"));
    EXPECT_EQ(Json(cmd::ColorSet("main")
                       .rangeMode(RangeMode::AllFrames)
                       .difference(ColorDifference::Mode::Change)),
              Json::parse(R"({"op":"color.set","view":"main","range_mode":"all",
                              "difference":"change"})"));
    EXPECT_EQ(Json(cmd::SurfaceSet("F").kernel(MetaballKernel::InverseSquare).color(std::nullopt)),
              Json::parse(R"({"op":"surface.set","fault":"F","kernel":"inverse-square",
                              "color":null})"));
    EXPECT_EQ(Json(cmd::Render("main", "m.mp4", 640, 480).frames(0, 9).step(2)),
              Json::parse(R"({"op":"render","view":"main","path":"m.mp4","size":[640,480],
                              "frames":[0,9],"step":2})"));
}

// What undo says of the batches the workbench makes around one change (issue 39: Accept all at
// another frame, and faults left empty deleted in the same step).
TEST(Commands, UndoLabelsOfGroupedChangesNameTheChange) {
    EXPECT_EQ(
        describeCommand(cmd::batch({cmd::FaultCreate("F1", {1, 2, 3}), cmd::faultDelete("A")})),
        "make fault F1 (3 spheres) (deleting A, left empty)");
    EXPECT_EQ(describeCommand(cmd::batch(
                  {cmd::frameSet(3), cmd::FaultCandidates().prefix("C"), cmd::frameSet(5)})),
              "accept the fault candidates");
    EXPECT_EQ(describeCommand(cmd::batch({cmd::faultDelete("A"), cmd::faultDelete("B")})),
              "delete 2 faults");
    EXPECT_EQ(describeCommand(cmd::batch({cmd::ThresholdAdd("strain"), cmd::boxRemove("b")})),
              "2 changes");
    EXPECT_EQ(describeCommand(cmd::batch({cmd::StrainAdd().sinceOffset(-1).prefix("inc_"),
                                          cmd::ColorSet("main").variable("inc_shear_strain")})),
              "add strain from motion (inc_*), coloured by inc_shear_strain");
}
