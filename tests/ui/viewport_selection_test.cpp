// Building faults in the viewport, headless: the command a pick makes (faultEdit), and scripted
// gestures on the 4 x 4 x 4 lattice seen from above: a rectangle, Ctrl+click toggling one
// sphere, a Shift+lasso making a new fault, Ctrl+rectangle removing, undo; orbit and pan intact.
#include "panel_fixture.hpp"
#include "ui/panels/viewport_selection.hpp"

#include "ui/viewport/fault_edit.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <algorithm>

using namespace faultline;
using namespace faultline::test;
using core::Json;

TEST(FaultEdit, AddsRemovesTogglesAndCreatesWithOnlyWhatChanges) {
    core::SessionState s;
    core::Fault f1;
    f1.name = "F1";
    f1.ids = {1, 2, 3};
    s.faults.push_back(f1);
    const std::set<std::string> sel{"F1"}, none;

    auto e = ui::faultEdit(s, sel, {5, 2, 4, 4}, ui::FaultEditOp::Add);
    EXPECT_EQ(e.command, (Json{{"op", "fault.add"}, {"name", "F1"}, {"ids", {4, 5}}}));
    EXPECT_TRUE(e.selectNext.empty());
    e = ui::faultEdit(s, sel, {5, 2, 3}, ui::FaultEditOp::Remove);
    EXPECT_EQ(e.command, (Json{{"op", "fault.remove"}, {"name", "F1"}, {"ids", {2, 3}}}));
    e = ui::faultEdit(s, sel, {2}, ui::FaultEditOp::Toggle);
    EXPECT_EQ(e.command, (Json{{"op", "fault.remove"}, {"name", "F1"}, {"ids", {2}}}));
    e = ui::faultEdit(s, sel, {9}, ui::FaultEditOp::Toggle);
    EXPECT_EQ(e.command, (Json{{"op", "fault.add"}, {"name", "F1"}, {"ids", {9}}}));
    e = ui::faultEdit(s, sel, {7, 6}, ui::FaultEditOp::NewFault);
    EXPECT_EQ(e.command, (Json{{"op", "fault.create"}, {"name", "F2"}, {"ids", {6, 7}}}));
    EXPECT_EQ(e.selectNext, "F2");
    // Nothing selected: adding (or toggling) makes a new fault; removing explains itself.
    e = ui::faultEdit(s, none, {9}, ui::FaultEditOp::Toggle);
    EXPECT_EQ(e.command, (Json{{"op", "fault.create"}, {"name", "F2"}, {"ids", {9}}}));
    e = ui::faultEdit(s, none, {1}, ui::FaultEditOp::Remove);
    EXPECT_TRUE(e.command.is_null());
    EXPECT_FALSE(e.message.empty());
    // Nothing changes: no command.
    EXPECT_TRUE(ui::faultEdit(s, sel, {1, 2}, ui::FaultEditOp::Add).command.is_null());
    EXPECT_TRUE(ui::faultEdit(s, sel, {8}, ui::FaultEditOp::Remove).command.is_null());
    EXPECT_TRUE(ui::faultEdit(s, sel, {}, ui::FaultEditOp::Add).command.is_null());
}

namespace {

// The lattice from (almost) straight above, and where each sphere's centre is on screen.
class SelectionTest : public PanelTest {
  protected:
    void SetUp() override {
        PanelTest::SetUp();
        openLattice();
        session.apply(
            Json::parse(R"({"op":"camera.set","view":"main","azimuth":0,"elevation":89})"));
        headless.frames(wb(), 3);
        headless.clearEmitted();
        img = headless.rect(wb(), "view.image.main");
        const ui::ViewDisplay& d = *wb().mainDisplay();
        const double w = img.x1 - img.x0, h = img.y1 - img.y0;
        const glm::dmat4 vp =
            ui::projectionMatrix(d.camera, w / h, d.sceneRadius) * ui::viewMatrix(d.camera);
        const core::Frame& f = *d.frame;
        for (std::size_t r = 0; r < f.size(); ++r) {
            auto p = ui::projectToPixels(vp, glm::dvec3(f.x[r], f.y[r], f.z[r]), glm::dvec2(w, h));
            ASSERT_TRUE(p);
            at[f.ids[r]] = ImVec2(img.x0 + float(p->x), img.y0 + float(p->y));
        }
    }
    // Lattice id of (x, y, z).
    static std::int64_t id(int x, int y, int z) { return 1 + x + 4 * y + 16 * z; }
    // Screen bounds of these spheres' centres, widened by `margin` pixels; checks no other
    // centre falls inside.
    std::pair<ImVec2, ImVec2> boundsOf(const std::vector<std::int64_t>& ids, float margin = 4) {
        ImVec2 lo(1e9f, 1e9f), hi(-1e9f, -1e9f);
        for (auto i : ids)
            lo = ImVec2(std::min(lo.x, at[i].x), std::min(lo.y, at[i].y)),
            hi = ImVec2(std::max(hi.x, at[i].x), std::max(hi.y, at[i].y));
        lo = ImVec2(lo.x - margin, lo.y - margin), hi = ImVec2(hi.x + margin, hi.y + margin);
        for (const auto& [i, p] : at)
            if (std::find(ids.begin(), ids.end(), i) == ids.end()) {
                EXPECT_FALSE(p.x >= lo.x - 2 && p.x <= hi.x + 2 && p.y >= lo.y - 2 &&
                             p.y <= hi.y + 2)
                    << "sphere " << i << " is too close";
            }
        return {lo, hi};
    }
    void withKeys(bool ctrl, bool shift, const std::function<void()>& gesture) {
        ImGui::GetIO().KeyCtrl = ctrl;
        ImGui::GetIO().KeyShift = shift;
        gesture();
        ImGui::GetIO().KeyCtrl = ImGui::GetIO().KeyShift = false;
        headless.frames(wb());
    }
    std::vector<std::int64_t> column(std::initializer_list<int> xs) {
        std::vector<std::int64_t> ids;
        for (int x : xs)
            for (int y = 0; y < 4; ++y)
                for (int z = 0; z < 4; ++z)
                    ids.push_back(id(x, y, z));
        std::sort(ids.begin(), ids.end());
        return ids;
    }

    ui::ItemRect img;
    std::map<std::int64_t, ImVec2> at;
};

} // namespace

// Issue 41: by default a rectangle takes the spheres in view; from above, the top layer.
// A pick that takes every sphere of another fault deletes that fault in the same step, and
// says so (an empty fault left in the list, the legend and the metrics confused users).
TEST(FaultEdit, AFaultLeftEmptyIsDeletedInTheSameStep) {
    core::SessionState s;
    core::Fault a, b;
    a.name = "A", a.ids = {1, 2};
    b.name = "B", b.ids = {3, 4, 5};
    s.faults = {a, b};
    auto e = ui::faultEdit(s, {}, {1, 2, 3}, ui::FaultEditOp::NewFault); // all of A, part of B
    EXPECT_EQ(e.command, (Json{{"op", "batch"},
                               {"commands",
                                {{{"op", "fault.create"}, {"name", "F1"}, {"ids", {1, 2, 3}}},
                                 {{"op", "fault.delete"}, {"name", "A"}}}}}));
    EXPECT_NE(e.message.find("A was left empty and deleted"), std::string::npos) << e.message;
    e = ui::faultEdit(s, {"B"}, {1, 2}, ui::FaultEditOp::Add); // A's spheres into B
    ASSERT_EQ(e.command["op"], "batch");
    EXPECT_EQ(e.command["commands"][1], (Json{{"op", "fault.delete"}, {"name", "A"}}));
    e = ui::faultEdit(s, {"B"}, {1}, ui::FaultEditOp::Add); // half of A: nothing deleted
    EXPECT_EQ(e.command["op"], "fault.add");
}

TEST_F(SelectionTest, ARectangleTakesTheSpheresInViewUnlessThroughTheDepth) {
    headless.click(wb(), "viewports.tool.rectangle");
    EXPECT_FALSE(wb().selection().throughDepth);
    const auto left = column({0, 1});
    auto [lo, hi] = boundsOf(left);
    headless.drag(wb(), lo.x, lo.y, hi.x, hi.y, 5, 0);
    std::vector<std::int64_t> top;
    for (int x : {0, 1})
        for (int y = 0; y < 4; ++y)
            top.push_back(id(x, y, 3));
    std::sort(top.begin(), top.end());
    ASSERT_EQ(headless.emitted().size(), 1u);
    const Json first = headless.emitted()[0];
    EXPECT_EQ(first["op"], "fault.create");
    // The top layer, and what the perspective shows of the block's outer faces; no inner sphere.
    std::vector<std::int64_t> taken = first["ids"].get<std::vector<std::int64_t>>();
    for (auto t : top)
        EXPECT_NE(std::find(taken.begin(), taken.end(), t), taken.end()) << t;
    for (auto t : taken) {
        const int x = int((t - 1) % 4), y = int((t - 1) / 4 % 4), z = int((t - 1) / 16);
        EXPECT_TRUE(z == 3 || x == 0 || y == 0 || y == 3) << t << " is inside the block";
    }
    EXPECT_LT(taken.size(), left.size() / 2);
    // Through the depth (the checkbox beside the tools): every layer under the rectangle.
    headless.click(wb(), "viewports.through_depth");
    EXPECT_TRUE(wb().selection().throughDepth);
    headless.clearEmitted();
    headless.drag(wb(), lo.x, lo.y, hi.x, hi.y, 5, 0);
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["ids"].size(), left.size() - taken.size());
}

TEST_F(SelectionTest, RectangleCtrlClickLassoAndRemoveAreOneCommandEach) {
    wb().selection().throughDepth = true; // whole columns, as OVITO's fence selection
    // 1. Rectangle tool, a drag around the spheres with x in {0, 1}: a new fault of them.
    headless.click(wb(), "viewports.tool.rectangle");
    EXPECT_EQ(wb().selection().tool, ui::ViewportTool::Rectangle);
    const auto left = column({0, 1});
    auto [lo, hi] = boundsOf(left);
    headless.drag(wb(), lo.x, lo.y, hi.x, hi.y, 5, 0,
                  [&] { EXPECT_TRUE(headless.emitted().empty()); });
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0], (Json{{"op", "fault.create"}, {"name", "F1"}, {"ids", left}}));
    EXPECT_EQ(wb().selection().faults, std::set<std::string>{"F1"});
    EXPECT_EQ(session.state().fault("F1")->ids, left);

    // 2. Back to orbiting (Esc); Ctrl+click the top sphere of the far corner adds it, again
    //    takes it out.
    headless.key(wb(), GLFW_KEY_ESCAPE);
    EXPECT_EQ(wb().selection().tool, ui::ViewportTool::Orbit);
    headless.clearEmitted();
    const ImVec2 corner = at[id(3, 3, 3)];
    withKeys(true, false, [&] { headless.clickAt(wb(), corner.x, corner.y); });
    withKeys(true, false, [&] { headless.clickAt(wb(), corner.x, corner.y); });
    EXPECT_EQ(headless.emitted(),
              (std::vector<Json>{{{"op", "fault.add"}, {"name", "F1"}, {"ids", {64}}},
                                 {{"op", "fault.remove"}, {"name", "F1"}, {"ids", {64}}}}));
    EXPECT_EQ(session.state().fault("F1")->ids, left);

    // 3. Lasso (L) with Shift around the column x = 3, y = 0: a new fault of its four spheres.
    headless.key(wb(), GLFW_KEY_L);
    EXPECT_EQ(wb().selection().tool, ui::ViewportTool::Lasso);
    headless.clearEmitted();
    const std::vector<std::int64_t> post{id(3, 0, 0), id(3, 0, 1), id(3, 0, 2), id(3, 0, 3)};
    // Named copies: clang 14's lambdas cannot capture structured bindings.
    const auto postBounds = boundsOf(post);
    const ImVec2 plo = postBounds.first, phi = postBounds.second;
    withKeys(false, true, [&] {
        headless.moveTo(wb(), plo.x, plo.y);
        headless.button(wb(), 0, true);
        for (ImVec2 p : {ImVec2(phi.x, plo.y), ImVec2(phi.x, phi.y), ImVec2(plo.x, phi.y),
                         ImVec2(plo.x, plo.y + 3)})
            headless.moveTo(wb(), p.x, p.y);
        EXPECT_TRUE(headless.emitted().empty());
        headless.button(wb(), 0, false);
    });
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0], (Json{{"op", "fault.create"}, {"name", "F2"}, {"ids", post}}));
    EXPECT_EQ(wb().selection().faults, std::set<std::string>{"F2"});

    // 4. Ctrl+rectangle over the x = 0 spheres removes them from F1.
    wb().selection().faults = {"F1"};
    headless.key(wb(), GLFW_KEY_R);
    headless.clearEmitted();
    const auto first = column({0});
    const auto firstBounds = boundsOf(first); // (clang 14: no bindings in lambdas)
    const ImVec2 rlo = firstBounds.first, rhi = firstBounds.second;
    withKeys(true, false, [&] { headless.drag(wb(), rlo.x, rlo.y, rhi.x, rhi.y); });
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0],
              (Json{{"op", "fault.remove"}, {"name", "F1"}, {"ids", first}}));
    EXPECT_EQ(session.state().fault("F1")->ids, column({1}));

    // Undo puts them back; the camera never moved.
    headless.key(wb(), GLFW_KEY_Z, true);
    EXPECT_EQ(session.state().fault("F1")->ids, left);
    EXPECT_TRUE(headless.emitted("camera.set").empty());

    // A Ctrl+drag without a tool still orbits, as it did before Ctrl+click picked spheres.
    headless.key(wb(), GLFW_KEY_ESCAPE);
    headless.clearEmitted();
    withKeys(true, false,
             [&] { headless.drag(wb(), img.cx(), img.cy(), img.cx() + 60, img.cy(), 4); });
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["op"], "camera.set");
    EXPECT_NEAR(session.state().view("main")->camera.azimuth, 360.0 - 60 * 0.3, 1e-9);

    // A right drag still pans with a selection tool on.
    headless.key(wb(), GLFW_KEY_R);
    headless.clearEmitted();
    headless.drag(wb(), img.cx(), img.cy(), img.cx() + 40, img.cy(), 4, 1);
    ASSERT_EQ(headless.emitted().size(), 1u);
    EXPECT_EQ(headless.emitted()[0]["op"], "camera.set");
}

TEST_F(SelectionTest, HiddenSpheresAreNotSelected) {
    // Only the top layer is visible: a rectangle over everything takes its 16 spheres.
    session.apply(Json::parse(R"({"op":"threshold.add","variable":"layer","low":3,"high":3})"));
    headless.frames(wb(), 2);
    headless.key(wb(), GLFW_KEY_R);
    headless.clearEmitted();
    headless.drag(wb(), img.x0 + 3, img.y0 + 3, img.x1 - 3, img.y1 - 3);
    ASSERT_EQ(headless.emitted().size(), 1u);
    std::vector<std::int64_t> top;
    for (std::int64_t i = 49; i <= 64; ++i)
        top.push_back(i);
    EXPECT_EQ(headless.emitted()[0], (Json{{"op", "fault.create"}, {"name", "F1"}, {"ids", top}}));
}

// Issue 27: member dots follow the spheres' size on screen: in a whole-model view (spheres a
// pixel or two across) they are one pixel without a dark ring, so the view does not turn black.
TEST(MemberMarkers, DotsFollowTheSpheresSizeOnScreen) {
    EXPECT_FLOAT_EQ(ui::memberMarkerRadius(1.0f, 1.2f, 1.0f), 1.0f);  // sphere 2.4 px across
    EXPECT_FLOAT_EQ(ui::memberMarkerRadius(1.0f, 5.0f, 1.0f), 2.25f); // sphere 10 px across
    EXPECT_FLOAT_EQ(ui::memberMarkerRadius(1.0f, 80.0f, 1.0f), 3.0f); // zoomed in: capped
    EXPECT_FLOAT_EQ(ui::memberMarkerRadius(1.0f, 80.0f, 2.0f), 6.0f); // HiDPI scale
}
