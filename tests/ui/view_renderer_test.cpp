// The viewports with the renderer's mock back end: what goes to the GPU and when. A frame's
// positions go up once, a drag re-sends only the visible rows, an idle UI draws nothing again.
#include "panel_fixture.hpp"

#include "ui/dock/panel_ids.hpp"
#include "ui/render/mock_renderer.hpp"
#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/viewport/orbit_camera.hpp"

using namespace faultline;
using namespace faultline::test;
using core::Json;

namespace {

// Calls of one kind (with a non-empty payload when `nonEmpty`).
std::size_t countCalls(const ui::MockRenderer& r, const std::string& what, bool nonEmpty = false) {
    std::size_t n = 0;
    for (const auto& c : r.calls())
        n += c.what == what && (!nonEmpty || c.count > 0);
    return n;
}

} // namespace

TEST_F(PanelTest, ViewsUploadOnlyWhatChangedAndSkipUnchangedDraws) {
    ui::GlViewRenderer renderer(ui::RendererBackend::Mock);
    wb().setRenderer(&renderer);
    openLattice();
    headless.frames(wb(), 3);
    auto* mock = dynamic_cast<ui::MockRenderer*>(renderer.rendererOf("main"));
    ASSERT_NE(mock, nullptr);
    EXPECT_EQ(countCalls(*mock, "upload.positions"), 1u);
    EXPECT_EQ(mock->visibleRows().size(), 64u);
    const std::size_t draws = renderer.drawCount();
    EXPECT_GE(draws, 1u);
    headless.frames(wb(), 10);
    EXPECT_EQ(renderer.drawCount(), draws) << "an idle UI must not redraw the views";

    // A threshold dragged on a histogram: the visible rows change each frame, positions stay.
    const ui::ItemRect r = headless.rect(wb(), "histogram.layer");
    headless.drag(wb(), r.x0 + (r.x1 - r.x0) * 0.3f, r.cy(), r.x0 + (r.x1 - r.x0) * 0.7f, r.cy());
    EXPECT_GT(renderer.drawCount(), draws);
    EXPECT_EQ(countCalls(*mock, "upload.positions"), 1u);
    EXPECT_EQ(mock->visibleRows().size(), 32u);

    // Colouring by a variable sends its values once; another frame sends positions again.
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","variable":"strain","range":[0,1]})"));
    headless.frames(wb(), 2);
    EXPECT_EQ(countCalls(*mock, "upload.values", true), 1u);
    EXPECT_EQ(mock->colorRange(), (core::ValueRange{0, 1}));
    session.apply(Json::parse(R"({"op":"frame.set","frame":1})"));
    headless.settle(wb());
    EXPECT_EQ(countCalls(*mock, "upload.positions"), 2u);

    // A second view gets its own renderer; removing it frees it.
    session.apply(Json::parse(R"({"op":"view.add","name":"before","frame":0})"));
    headless.settle(wb());
    EXPECT_NE(renderer.rendererOf("before"), nullptr);
    session.apply(Json::parse(R"({"op":"view.remove","name":"before"})"));
    headless.frames(wb(), 2);
    EXPECT_EQ(renderer.rendererOf("before"), nullptr);
    wb().setRenderer(nullptr);
}

TEST(RenderCamera, MatchesTheOrbitCameraOfTheViewport) {
    core::CameraState c;
    c.target = {1, 2, 3};
    c.distance = 10;
    c.azimuth = 30;
    c.elevation = 25;
    const core::Camera cam = ui::toRenderCamera(c);
    const ui::CameraBasis b = ui::cameraBasis(c);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(cam.eye()[k], b.eye[k], 1e-9);
        EXPECT_NEAR(cam.up()[k], b.up[k], 1e-9);
        EXPECT_NEAR(cam.right()[k], b.right[k], 1e-9);
    }
}
