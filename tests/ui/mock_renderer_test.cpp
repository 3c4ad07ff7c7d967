// The renderer contract through the Mock back end: no display needed.
#include "test_scenes.hpp"
#include "ui/render/mock_renderer.hpp"
#include "ui/render/offscreen.hpp"

#include <gtest/gtest.h>

using namespace faultline;
using namespace faultline::ui;

namespace {
std::size_t countOf(const std::vector<MockCall>& calls, const std::string& what) {
    std::size_t n = 0;
    for (const MockCall& c : calls)
        n += c.what == what;
    return n;
}
const MockCall* find(const std::vector<MockCall>& calls, const std::string& what) {
    for (const MockCall& c : calls)
        if (c.what == what)
            return &c;
    return nullptr;
}
} // namespace

TEST(MockRenderer, FactoryMakesTheMock) {
    auto r = createRenderer(RendererBackend::Mock);
    EXPECT_EQ(r->backend(), RendererBackend::Mock);
    EXPECT_EQ(r->colorTexture(), 0u);
}

TEST(MockRenderer, ColourChangesDoNotResendPositions) {
    const core::Frame f = test::makeLattice(4, 3, 2);
    MockRenderer r;
    r.setSpheres({f.x, f.y, f.z, f.radius});
    r.setSphereValues(f.attribute("strain")->floats);
    r.setColorMap({core::ColorMapKind::Viridis});
    r.setColorRange({0.0, 0.5});
    r.setColorMap({core::ColorMapKind::Pastel});
    r.setColorRange({0.1, 0.3});
    EXPECT_EQ(r.stats().positionUploads, 1u);
    EXPECT_EQ(r.stats().valueUploads, 1u);
    EXPECT_EQ(r.stats().colorMapUploads, 2u);
    EXPECT_EQ(countOf(r.calls(), "upload.positions"), 1u);
    EXPECT_EQ(r.colorRange(), (core::ValueRange{0.1, 0.3}));
}

TEST(MockRenderer, HiddenSpheresAreNotDrawn) {
    const core::Frame f = test::makeLattice(5, 2, 1); // 10 spheres
    MockRenderer r;
    r.setSpheres({f.x, f.y, f.z, f.radius});
    std::vector<std::uint8_t> mask(10, 0);
    mask[1] = mask[4] = mask[7] = 1;
    r.setVisibleMask(mask);
    EXPECT_EQ(r.visibleRows(), (std::vector<std::uint32_t>{1, 4, 7}));
    EXPECT_EQ(r.stats().positionUploads, 1u); // visibility does not re-send positions

    core::Camera cam;
    r.render(cam, {64, 48});
    auto frame = r.lastFrame();
    ASSERT_TRUE(find(frame, "draw.spheres"));
    EXPECT_EQ(find(frame, "draw.spheres")->count, 3u);
    EXPECT_FALSE(find(frame, "draw.context_points"));
    EXPECT_FALSE(find(frame, "draw.legend")); // no values: no legend

    RenderStyle style;
    style.contextPoints = true;
    r.setStyle(style);
    r.render(cam, {64, 48});
    frame = r.lastFrame();
    ASSERT_TRUE(find(frame, "draw.context_points"));
    EXPECT_EQ(find(frame, "draw.context_points")->count, 7u);
    EXPECT_EQ(r.stats().visibleSpheres, 3u);
    EXPECT_EQ(r.stats().contextPoints, 7u);

    r.setVisibleMask({}); // all visible again
    r.render(cam, {64, 48});
    EXPECT_EQ(find(r.lastFrame(), "draw.spheres")->count, 10u);
}

TEST(MockRenderer, LegendBoxesHandlesAndMeshes) {
    const core::Frame f = test::makeLattice(3, 3, 3);
    MockRenderer r;
    r.setSpheres({f.x, f.y, f.z, f.radius});
    r.setSphereValues(f.attribute("height")->floats);
    r.setColorRange({0.0, 2.0});
    MeshData tri;
    tri.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    tri.indices = {0, 1, 2};
    r.setMeshes(std::span<const MeshData>(&tri, 1));
    const BoxOverlay boxes[2] = {{{0, 0, 0}, {1, 1, 1}, {1, 0, 0}},
                                 {{1, 1, 1}, {2, 2, 2}, {0, 0, 1}}};
    r.setBoxes(boxes, BoxHandlesOverlay{1, 0.0, core::BoxFace::MaxZ});
    r.render(core::Camera{}, {320, 240, 2, true});
    const auto frame = r.lastFrame();
    EXPECT_EQ(find(frame, "draw.meshes")->count, 1u);
    EXPECT_EQ(find(frame, "draw.box_edges")->count, 24u);
    EXPECT_EQ(find(frame, "draw.handles")->count, 6u);
    EXPECT_EQ(find(frame, "post.downsample")->count, 2u);
    EXPECT_EQ(find(frame, "draw.legend")->count, 5u); // 0, 0.5, 1, 1.5, 2
    EXPECT_EQ(find(frame, "clear")->count, 0u);       // transparent
    const RgbaImage img = r.readImage();
    EXPECT_EQ(img.width, 320);
    EXPECT_EQ(img.pixels[3], 0); // transparent background
    // Bounds take in spheres, the mesh and the boxes.
    const core::BoundingSphere b = r.sceneBounds();
    EXPECT_GT(b.radius, 1.7);
}

TEST(MockRenderer, LoadSceneFromADescription) {
    const core::Frame f = test::makeLattice(4, 4, 4);
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "layer";
    scene.colorMap = *core::parseColorMap("bands:4");
    scene.visible.assign(f.size(), 1);
    scene.visible[0] = 0;
    MockRenderer r;
    loadScene(r, scene);
    EXPECT_EQ(r.visibleRows().size(), f.size() - 1);
    EXPECT_EQ(r.colorRange(), (core::ValueRange{0.0, 3.0})); // the column's min..max
    EXPECT_EQ(r.colorMap().bands, 4);

    scene.colorVariable = "no_such_thing";
    EXPECT_THROW(loadScene(r, scene), std::invalid_argument);
    scene.colorVariable.clear();
    scene.visible.assign(3, 1);
    EXPECT_THROW(loadScene(r, scene), std::invalid_argument);
}

TEST(MockRenderer, FittedCameraSeesTheVisibleSpheres) {
    const core::Frame f = test::makeLattice(10, 10, 10);
    SceneDescription scene;
    scene.frame = &f;
    scene.visible.assign(f.size(), 0);
    scene.visible[0] = 1; // only the sphere at the origin
    const core::Camera cam = fittedCamera(scene, 100, 100, core::ViewPreset::Top);
    EXPECT_NEAR(cam.target.x, 0.0, 1e-9);
    EXPECT_NEAR(cam.target.y, 0.0, 1e-9);
    EXPECT_LT(cam.distance, 5.0);
}
