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

// A long sandbox seen end-on beside a colour legend (the strain bench's 69 x 421 x 22 block
// from the front): in perspective its near face is far nearer the eye than the box's middle,
// and moving the target by half the legend at the middle's depth moved that face twice as far,
// out of the view's left edge. Every corner must project inside the view, left of the legend,
// and the box must fill the room it has (neither side far from its edge).
TEST(RenderCamera, FitBesideALegendKeepsADeepBoxInTheRoomLeft) {
    const std::array<double, 3> lo{0.65, 0.0, 0.56}, hi{68.4, 420.0, 21.4};
    const double width = 950, height = 700, legend = 140;
    for (const char* preset : {"front", "side", "iso", "top"})
        for (const bool ortho : {false, true}) {
            core::CameraState c;
            c.orthographic = ortho;
            ui::applyPreset(c, preset);
            ui::fitBesideLegend(c, lo, hi, width, height, legend);
            const glm::dmat4 vp =
                ui::projectionMatrix(c, width / height, 300.0) * ui::viewMatrix(c);
            double left = width, right = 0, top = height, bottom = 0;
            for (int k = 0; k < 8; ++k) {
                const auto p = ui::projectToPixels(
                    vp,
                    glm::dvec3(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]),
                    {width, height});
                ASSERT_TRUE(p) << preset;
                left = std::min(left, p->x), right = std::max(right, p->x);
                top = std::min(top, p->y), bottom = std::max(bottom, p->y);
            }
            SCOPED_TRACE(std::string(preset) + (ortho ? ", orthographic" : ", perspective"));
            EXPECT_GE(left, 0.0);
            EXPECT_LE(right, width - legend);
            EXPECT_GE(top, 0.0);
            EXPECT_LE(bottom, height);
            // Centred across the room left of the legend, and as large as it allows: its sides,
            // or its top or bottom, within the margin.
            EXPECT_NEAR(left, width - legend - right, 2.0);
            EXPECT_TRUE(left < 0.06 * width || std::min(top, height - bottom) < 0.06 * height);
        }
}
