// Headless runs of the Data, Cutting boxes, Thresholds and Histograms panels: scripted mouse
// input, checking the commands emitted and what the views show while dragging.
#include "panel_fixture.hpp"

#include "ui/dock/panel_ids.hpp"

using namespace faultline;
using namespace faultline::test;
using core::Json;

TEST_F(PanelTest, DataPanelOpensInTheBackgroundThenCloses) {
    const std::string path = writeLattice(dir.file("lattice.dump"));
    wb().opener().openData({path});
    EXPECT_EQ(session.dataset(), nullptr); // nothing changes until the job is done
    headless.settle(wb());
    ASSERT_EQ(headless.emitted("data.open").size(), 1u);
    EXPECT_EQ(headless.emitted("data.open")[0], (Json{{"op", "data.open"}, {"paths", {path}}}));
    ASSERT_NE(session.dataset(), nullptr);
    EXPECT_EQ(visible(), 64u);
    headless.showPanel(wb(), ui::panel_ids::kData);
    headless.click(wb(), "data.close");
    ASSERT_EQ(headless.emitted("data.close").size(), 1u);
    EXPECT_EQ(session.dataset(), nullptr);
    EXPECT_EQ(wb().mainDisplay()->frame, nullptr);
}

TEST_F(PanelTest, AMissingFileIsReportedNotFatal) {
    wb().opener().openData({dir.file("nothing-here.dump")});
    headless.settle(wb());
    EXPECT_TRUE(headless.emitted().empty());
    EXPECT_TRUE(wb().lastMessageIsError());
    EXPECT_NE(wb().lastMessage().find("nothing-here.dump"), std::string::npos)
        << wb().lastMessage();
}

TEST_F(PanelTest, BoxesPanelAddsEditsDuplicatesAndDeletes) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kBoxes);
    headless.click(wb(), "boxes.add");
    const Json expected = {{"op", "box.add"},
                           {"name", "box 1"},
                           {"min", {-0.5, -0.5, -0.5}},
                           {"max", {3.5, 3.5, 3.5}},
                           {"mode", "keep"}};
    ASSERT_EQ(headless.emitted(), std::vector<Json>{expected});
    EXPECT_EQ(wb().selection().box, "box 1");
    EXPECT_EQ(visible(), 64u);

    // Drag the x slider's high end to the middle: the view follows during the drag, one command
    // on release.
    headless.frames(wb(), 2);
    headless.clearEmitted();
    const ui::ItemRect r = headless.rect(wb(), "boxes.fraction.0");
    const float grab = std::max(6.0f, (r.y1 - r.y0) * 0.35f);
    std::size_t visibleWhileHeld = 0;
    double maxWhileHeld = 0;
    headless.drag(wb(), r.x1 - grab, r.cy(), r.x0 + grab + (r.x1 - r.x0 - 2 * grab) * 0.5f, r.cy(),
                  6, 0, [&] {
                      visibleWhileHeld = visible();
                      maxWhileHeld = wb().displayBoxes().at(0).max[0];
                      EXPECT_TRUE(headless.emitted().empty()) << "no command before the release";
                  });
    EXPECT_NEAR(maxWhileHeld, 1.5, 0.05); // half of [-0.5, 3.5]
    EXPECT_EQ(visibleWhileHeld, 32u);     // x in {0, 1}
    ASSERT_EQ(headless.emitted("box.set").size(), 1u);
    EXPECT_EQ(headless.emitted().size(), 1u);
    EXPECT_NEAR(session.state().box("box 1")->max[0], 1.5, 0.05);
    EXPECT_EQ(visible(), 32u);

    headless.clearEmitted();
    headless.click(wb(), "boxes.enabled.box 1");
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "box.set"}, {"name", "box 1"}, {"enabled", false}}}));
    EXPECT_EQ(visible(), 64u);
    headless.click(wb(), "boxes.duplicate");
    ASSERT_EQ(headless.emitted("box.add").size(), 1u);
    EXPECT_EQ(headless.emitted("box.add")[0]["name"], "box 1 1");
    EXPECT_EQ(wb().selection().box, "box 1 1");
    headless.click(wb(), "boxes.delete");
    EXPECT_EQ(headless.emitted("box.remove").back(),
              (Json{{"op", "box.remove"}, {"name", "box 1 1"}}));
    EXPECT_EQ(session.state().boxes.size(), 1u);

    // Ctrl+Z undoes the delete.
    headless.key(wb(), GLFW_KEY_Z, true);
    EXPECT_EQ(headless.emitted().back(), (Json{{"op", "undo"}}));
    EXPECT_EQ(session.state().boxes.size(), 2u);
    headless.key(wb(), GLFW_KEY_Z, true, true);
    EXPECT_EQ(headless.emitted().back(), (Json{{"op", "redo"}}));
    EXPECT_EQ(session.state().boxes.size(), 1u);
}

TEST_F(PanelTest, ThresholdsPanelAddsSlidesInWholeValuesDisablesAndRemoves) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kThresholds);
    headless.click(wb(), "thresholds.add");
    headless.frames(wb(), 2);
    headless.click(wb(), "thresholds.add.layer");
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0],
              (Json{{"op", "threshold.add"}, {"variable", "layer"}, {"low", 0.0}, {"high", 3.0}}));
    headless.frames(wb(), 2);
    headless.clearEmitted();

    // The low handle from 0 to 40% of [0, 3]: 1.2 -> 1, an integer column moves by whole values.
    const ui::ItemRect r = headless.rect(wb(), "thresholds.slider.layer");
    const float grab = std::max(6.0f, (r.y1 - r.y0) * 0.35f);
    const float x0 = r.x0 + grab, x1 = r.x1 - grab;
    std::size_t visibleWhileHeld = 0;
    headless.drag(wb(), x0, r.cy(), x0 + (x1 - x0) * 0.4f, r.cy(), 5, 0,
                  [&] { visibleWhileHeld = visible(); });
    EXPECT_EQ(visibleWhileHeld, 48u); // layers 1..3
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{
                  {{"op", "threshold.set"}, {"variable", "layer"}, {"low", 1.0}, {"high", 3.0}}}));
    EXPECT_EQ(session.state().threshold("layer")->low, 1.0);

    // Typed bounds: a number, and an empty field for an open end.
    headless.clearEmitted();
    headless.retype(wb(), "thresholds.low.layer", "2.5", GLFW_KEY_ENTER);
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "threshold.set"}, {"variable", "layer"}, {"low", 3.0}}}));
    headless.clearEmitted();
    headless.click(wb(), "thresholds.high.layer");
    headless.key(wb(), GLFW_KEY_A, true);
    headless.key(wb(), GLFW_KEY_BACKSPACE);
    headless.key(wb(), GLFW_KEY_ENTER);
    EXPECT_EQ(
        headless.emitted(),
        (std::vector<Json>{{{"op", "threshold.set"}, {"variable", "layer"}, {"high", 1e30}}}));
    EXPECT_EQ(visible(), 16u); // layer 3 only

    headless.clearEmitted();
    headless.click(wb(), "thresholds.enabled.layer");
    EXPECT_EQ(
        headless.emitted(),
        (std::vector<Json>{{{"op", "threshold.set"}, {"variable", "layer"}, {"enabled", false}}}));
    EXPECT_EQ(visible(), 64u);
    headless.click(wb(), "thresholds.remove.layer");
    EXPECT_EQ(headless.emitted().back(), (Json{{"op", "threshold.remove"}, {"variable", "layer"}}));
    EXPECT_TRUE(session.state().thresholds.empty());
}

TEST_F(PanelTest, DraggingOnAHistogramSetsTheThresholdAndItsEdgesAdjustIt) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kHistograms);
    // Default histograms: the first columns, strain and layer. layer has integer bins [0, 4).
    const ui::ItemRect r = headless.rect(wb(), "histogram.layer");
    auto xAt = [&](double value) { return r.x0 + static_cast<float>(value / 4.0) * (r.x1 - r.x0); };
    std::size_t visibleWhileHeld = 0;
    headless.drag(wb(), xAt(1.2), r.cy(), xAt(2.8), r.cy(), 6, 0, [&] {
        visibleWhileHeld = visible();
        EXPECT_TRUE(headless.emitted().empty());
    });
    EXPECT_EQ(visibleWhileHeld, 32u); // layers 1 and 2
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0],
              (Json{{"op", "threshold.add"}, {"variable", "layer"}, {"low", 1.0}, {"high", 2.0}}));
    EXPECT_EQ(visible(), 32u);

    // The high edge (at 3, the right side of bar 2) dragged to the end: high 3.
    headless.clearEmitted();
    headless.drag(wb(), xAt(3.0), r.cy(), r.x1 - 1, r.cy());
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0],
              (Json{{"op", "threshold.set"}, {"variable", "layer"}, {"low", 1.0}, {"high", 3.0}}));
    EXPECT_EQ(visible(), 48u);

    // Log scale (on by default) is a panel setting kept with the layout.
    headless.clearEmitted();
    headless.click(wb(), "histograms.log");
    ASSERT_EQ(headless.emitted("layout.set").size(), 1u);
    EXPECT_EQ(session.state().dockLayout["panels"]["histograms"]["log"], false);
    EXPECT_EQ(session.state().dockLayout["panels"]["histograms"]["variables"],
              (Json{"strain", "layer"}));

    // A float variable: the drag covers about the middle of strain's range [0, 1].
    headless.clearEmitted();
    const ui::ItemRect s = headless.rect(wb(), "histogram.strain");
    headless.drag(wb(), s.x0 + (s.x1 - s.x0) * 0.5f, s.cy(), s.x1 - 1, s.cy());
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["op"], "threshold.add");
    EXPECT_NEAR(headless.emitted()[0]["low"].get<double>(), 0.5, 0.02);
    EXPECT_EQ(visible(), 24u); // x in {2, 3} and layer >= 1
}

// Issue 27: the default histograms keep their order when the colouring changes (they followed
// the colour variable to the top).
TEST_F(PanelTest, DefaultHistogramsKeepTheirOrderWhenTheColouringChanges) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kHistograms);
    headless.settle(wb());
    const float strainY = headless.rect(wb(), "histogram.strain").y0;
    const float layerY = headless.rect(wb(), "histogram.layer").y0;
    EXPECT_LT(strainY, layerY);
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"layer"})"));
    headless.settle(wb());
    EXPECT_FLOAT_EQ(headless.rect(wb(), "histogram.strain").y0, strainY);
    EXPECT_FLOAT_EQ(headless.rect(wb(), "histogram.layer").y0, layerY);
}

// A file of positions alone (as most DEM codes write) shows the radius histogram; strain from
// motion derived shows its first variables, and they come back after it is derived anew (the
// default list was kept from before, the radius alone).
// A 3 x 3 x 3 lattice of positions, stretched by 10 % along x in its second frame (strain from
// motion has a value there), with `columns` after the radius and the same `values` in each row.
class StretchedLatticeTest : public PanelTest {
  protected:
    void openStretchedLattice(const std::string& columns = "", const std::string& values = "") {
        std::string text;
        for (int t = 0; t < 2; ++t) {
            text += "ITEM: TIMESTEP\n" + std::to_string(t) +
                    "\nITEM: NUMBER OF ATOMS\n27\nITEM: BOX BOUNDS ff ff ff\n0 3\n0 3\n0 3\n"
                    "ITEM: ATOMS id x y z radius" +
                    columns + "\n";
            for (int id = 0; id < 27; ++id)
                text += std::to_string(id + 1) + " " + std::to_string(id % 3 * (1.0 + 0.1 * t)) +
                        " " + std::to_string(id / 3 % 3) + " " + std::to_string(id / 9) + " 0.5" +
                        values + "\n";
        }
        wb().opener().openData({dir.write("lattice2.dump", text)});
        headless.settle(wb());
        ASSERT_NE(session.dataset(), nullptr);
        headless.showPanel(wb(), ui::panel_ids::kHistograms);
        headless.settle(wb());
    }
    // Cumulative strain "inc_*" against frame 0, shown at frame 1.
    void deriveStrainAtFrameOne() {
        session.apply(Json::parse(R"({"op":"frame.set","frame":1})"));
        session.apply(Json::parse(R"({"op":"strain.add","since_frame":0,"prefix":"inc_"})"));
        headless.settle(wb());
    }
};

TEST_F(StretchedLatticeTest, DefaultHistogramsFollowTheStrainVariablesAsTheyComeAndGo) {
    openStretchedLattice();
    EXPECT_TRUE(headless.has(wb(), "histogram.radius"));
    deriveStrainAtFrameOne();
    EXPECT_TRUE(headless.has(wb(), "histogram.inc_shear_strain"));
    EXPECT_FALSE(headless.has(wb(), "histogram.radius"));
    session.apply(Json::parse(R"({"op":"strain.remove","prefix":"inc_"})"));
    headless.settle(wb());
    EXPECT_TRUE(headless.has(wb(), "histogram.radius"));
    session.apply(Json::parse(R"({"op":"strain.add","since_frame":0,"cutoff":1.5,"prefix":"c_"})"));
    headless.settle(wb());
    EXPECT_TRUE(headless.has(wb(), "histogram.c_shear_strain"));
    // Still the default list: nothing was saved as the user's choice.
    const Json* settings = std::as_const(wb().layout()).panelSettings(ui::panel_ids::kHistograms);
    EXPECT_TRUE(!settings || !settings->contains("variables"));
}

// LIGGGHTS writes type and velocities: strain from motion came after them, and the default
// histograms (the first three columns) never showed it. Its shear strain now comes first.
TEST_F(StretchedLatticeTest, DefaultHistogramsShowShearStrainBeforeTheFilesColumns) {
    openStretchedLattice(" type vx vy", " 1 0.1 0.2");
    EXPECT_TRUE(headless.has(wb(), "histogram.vx"));
    deriveStrainAtFrameOne();
    EXPECT_TRUE(headless.has(wb(), "histogram.inc_shear_strain"));
    EXPECT_TRUE(headless.has(wb(), "histogram.type"));
    EXPECT_TRUE(headless.has(wb(), "histogram.vx"));
    EXPECT_FALSE(headless.has(wb(), "histogram.vy"));
    EXPECT_LT(headless.rect(wb(), "histogram.inc_shear_strain").y0,
              headless.rect(wb(), "histogram.type").y0);
    ASSERT_TRUE(session.undo());
    headless.settle(wb());
    EXPECT_FALSE(headless.has(wb(), "histogram.inc_shear_strain"));
    EXPECT_TRUE(headless.has(wb(), "histogram.vy"));
}

// Incremental strain added on the first frame has no value there (no frame before it): the
// histogram's automatic bin count, which is kept for every frame after (and saved with the
// layout), came from that frame and was one bin: a solid block on every frame with values.
TEST_F(StretchedLatticeTest, AHistogramTakesItsBinsFromTheFirstFrameWithValues) {
    openStretchedLattice();
    auto savedBins = [&](const std::string& var) -> int {
        const Json* s = std::as_const(wb().layout()).panelSettings(ui::panel_ids::kHistograms);
        if (!s || !s->contains("bins") || !(*s)["bins"].contains(var))
            return 0;
        return (*s)["bins"][var].get<int>();
    };
    session.apply(Json::parse(R"({"op":"strain.add","since_offset":-1,"prefix":"inc_"})"));
    headless.settle(wb());
    ASSERT_TRUE(headless.has(wb(), "histogram.inc_shear_strain"));
    EXPECT_EQ(savedBins("inc_shear_strain"), 0) << "chosen on a frame without a value";
    session.apply(Json::parse(R"({"op":"frame.set","frame":1})"));
    headless.settle(wb());
    EXPECT_GT(savedBins("inc_shear_strain"), 1);

    // A session saved before this fix holds the one bin: chosen again.
    wb().layout().panelSettings(ui::panel_ids::kHistograms)["bins"]["c_shear_strain"] = 1;
    session.apply(Json::parse(R"({"op":"strain.add","since_frame":0,"prefix":"c_"})"));
    headless.settle(wb());
    ASSERT_TRUE(headless.has(wb(), "histogram.c_shear_strain"));
    EXPECT_GT(savedBins("c_shear_strain"), 1);
}

// Two extreme values in 400 (grains thrown out of a model, with strain in the hundreds)
// put every other value in the first bar. A button under the plot (and the plot's menu) shows the
// 1st to 99th percentile instead (kept with the layout), says how many lie beyond, and a
// threshold dragged to its right end still takes the extreme values.
TEST_F(PanelTest, AHistogramCanShowTheMiddleOfItsValues) {
    std::string text = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n400\nITEM: BOX BOUNDS ff ff ff\n"
                       "0 20\n0 20\n0 1\nITEM: ATOMS id x y z radius v\n";
    auto value = [](int id) { return id == 7 || id == 261 ? 1000.0 : id / 400.0; };
    for (int id = 0; id < 400; ++id)
        text += std::to_string(id + 1) + " " + std::to_string(id % 20) + " " +
                std::to_string(id / 20) + " 0 0.5 " + std::to_string(value(id)) + "\n";
    wb().opener().openData({dir.write("tail.dump", text)});
    headless.settle(wb());
    ASSERT_NE(session.dataset(), nullptr);
    headless.showPanel(wb(), ui::panel_ids::kHistograms);
    headless.settle(wb());
    ASSERT_TRUE(headless.has(wb(), "histogram.v"));
    EXPECT_FALSE(headless.has(wb(), "histogram.v.beyond"));
    // Under the plot, a button offers the middle view: all but two values fill a thousandth of
    // the axis.
    ASSERT_TRUE(headless.has(wb(), "histogram.v.offer-middle"));
    headless.click(wb(), "histogram.v.offer-middle");
    headless.frames(wb(), 2);
    EXPECT_EQ(session.state().dockLayout["panels"]["histograms"]["middle"]["v"], true);
    EXPECT_TRUE(headless.has(wb(), "histogram.v.beyond"));
    EXPECT_FALSE(headless.has(wb(), "histogram.v.offer-middle"));
    // And the plot's menu switches it, off and on.
    auto switchFromTheMenu = [&] {
        headless.click(wb(), "histogram.v", 1);
        headless.frames(wb(), 2);
        headless.click(wb(), "histogram.v.middle");
        headless.frames(wb(), 2);
        return session.state().dockLayout["panels"]["histograms"]["middle"].contains("v");
    };
    EXPECT_FALSE(switchFromTheMenu());
    EXPECT_TRUE(headless.has(wb(), "histogram.v.offer-middle"));
    EXPECT_TRUE(switchFromTheMenu());
    EXPECT_TRUE(headless.has(wb(), "histogram.v.beyond"));

    // From the middle of what is shown (about 0.5) to the right end: up to the largest value.
    headless.clearEmitted();
    const ui::ItemRect r = headless.rect(wb(), "histogram.v");
    headless.drag(wb(), r.x0 + (r.x1 - r.x0) * 0.5f, r.cy(), r.x1 - 1, r.cy());
    ASSERT_EQ(headless.emitted("threshold.add").size(), 1u);
    const Json add = headless.emitted("threshold.add")[0];
    const double low = add["low"].get<double>();
    EXPECT_NEAR(low, 0.5, 0.03);
    EXPECT_EQ(add["high"].get<double>(), 1000.0);
    std::size_t above = 0;
    for (int id = 0; id < 400; ++id)
        above += float(value(id)) >= low ? 1 : 0;
    EXPECT_EQ(visible(), above); // the two extremes among them

    // Off again: the whole range, nothing beyond.
    EXPECT_FALSE(switchFromTheMenu());
    EXPECT_FALSE(headless.has(wb(), "histogram.v.beyond"));
}

// Issue 41, item 12: reopening a session coloured by a variable showed the histograms in
// another order (the colour variable first).
TEST_F(PanelTest, DefaultHistogramsKeepTheirOrderAfterReopeningASession) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kHistograms);
    headless.settle(wb());
    const float strainY = headless.rect(wb(), "histogram.strain").y0;
    const float layerY = headless.rect(wb(), "histogram.layer").y0;
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"layer"})"));
    const std::string file = dir.file("h.faultline.json");
    session.apply({{"op", "session.save"}, {"path", file}});
    const auto again = reopen(file);
    ui::Workbench& reopened = again->wb;
    headless.showPanel(reopened, ui::panel_ids::kHistograms);
    headless.settle(reopened);
    EXPECT_FLOAT_EQ(headless.rect(reopened, "histogram.strain").y0, strainY);
    EXPECT_FLOAT_EQ(headless.rect(reopened, "histogram.layer").y0, layerY);
}

// Walkthrough of issue 41: a float variable's histogram had about 20 bins before saving and
// hundreds after reopening (its automatic bin count was chosen on the frame shown first: frame 0
// before, the saved frame after). The count chosen rides along in the session.
TEST_F(PanelTest, AHistogramKeepsItsBinsAfterReopeningAtAnotherFrame) {
    openLattice();
    headless.showPanel(wb(), ui::panel_ids::kHistograms);
    headless.settle(wb());
    const core::Json* settings =
        std::as_const(wb().layout()).panelSettings(ui::panel_ids::kHistograms);
    ASSERT_NE(settings, nullptr);
    ASSERT_TRUE(settings->contains("bins")) << settings->dump();
    const core::Json bins = (*settings)["bins"];
    ASSERT_TRUE(bins.contains("strain"));
    session.apply(Json::parse(R"({"op":"frame.set","frame":2})"));
    const std::string file = dir.file("bins.faultline.json");
    wb().saveSessionAs(file);
    headless.settle(wb());
    const auto again = reopen(file);
    ui::Workbench& reopened = again->wb;
    headless.showPanel(reopened, ui::panel_ids::kHistograms);
    headless.settle(reopened);
    const core::Json* restored =
        std::as_const(reopened.layout()).panelSettings(ui::panel_ids::kHistograms);
    ASSERT_NE(restored, nullptr);
    EXPECT_EQ((*restored)["bins"], bins) << "chosen again on frame 2";
}

// Issue 27: a box extent takes typing after one click; Enter commits one box.set, Escape puts
// the value back and commits nothing.
TEST_F(PanelTest, BoxExtentsTakeTypingAfterOneClickAndEscapeCancels) {
    openLattice();
    session.apply(core::Json::parse(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[3,3,3]})"));
    wb().selection().box = "b";
    headless.showPanel(wb(), ui::panel_ids::kBoxes);
    headless.settle(wb());
    headless.clearEmitted();
    headless.retype(wb(), "boxes.max.0", "2.5", GLFW_KEY_ENTER);
    headless.settle(wb());
    auto sets = headless.emitted("box.set");
    ASSERT_EQ(sets.size(), 1u);
    EXPECT_DOUBLE_EQ(sets[0]["max"][0].get<double>(), 2.5);
    EXPECT_DOUBLE_EQ(session.state().box("b")->max[0], 2.5);

    headless.clearEmitted();
    headless.retype(wb(), "boxes.min.1", "1.75", GLFW_KEY_ESCAPE);
    headless.settle(wb());
    EXPECT_TRUE(headless.emitted("box.set").empty());
    EXPECT_DOUBLE_EQ(session.state().box("b")->min[1], 0.0);
}

// Issue 41: a view's "this frame's min to max" spans the spheres it shows.
TEST_F(PanelTest, TheFramesColourRangeSpansTheSpheresShown) {
    openLattice();
    session.apply(Json{{"op", "color.set"}, {"view", "main"}, {"variable", "layer"}});
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorRange, (std::array<double, 2>{0, 3}));
    session.apply(Json{{"op", "threshold.add"}, {"variable", "layer"}, {"low", 1}, {"high", 2}});
    headless.settle(wb());
    ASSERT_EQ(visible(), 32u);
    EXPECT_EQ(wb().mainDisplay()->colorRange, (std::array<double, 2>{1, 2}));
    // "all frames seen" and "fixed" keep their meaning.
    session.apply(Json{{"op", "color.set"}, {"view", "main"}, {"range_mode", "all"}});
    headless.settle(wb());
    EXPECT_EQ(wb().mainDisplay()->colorRange, (std::array<double, 2>{0, 3}));
}
