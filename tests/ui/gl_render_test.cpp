// The OpenGL renderer on known scenes, compared with small reference images (mean absolute
// difference per channel). Skips without a display; run under xvfb-run with Mesa llvmpipe.
#include "core/selection/cutting_box.hpp"
#include "gl_required.hpp"
#include "test_scenes.hpp"
#include "ui/render/gl_renderer.hpp"
#include "ui/render/offscreen.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

using namespace faultline;
using namespace faultline::ui;

namespace {

// llvmpipe is deterministic on one machine; other drivers round differently.
constexpr double kTolerance = 1.5;
// Pixels allowed to differ by more than 48 of 255 in some channel (antialiasing on edges).
constexpr std::size_t kMaxDifferingPixels = 24;
// Mean SSIM of the luma (core/util/image_compare.hpp): the references score 0.99 or more.
constexpr double kMinSsim = 0.97;

class GlRender : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string why;
        if (!sharedOffscreenContext(why))
            FAULTLINE_NEED_GL("no OpenGL context: " << why);
    }

    // Renders, saves the image next to the build, and compares with tests/ui/ref/<name>.png
    // (or rewrites the reference when FAULTLINE_UPDATE_REFS=1).
    void compareWithReference(const RgbaImage& image, const std::string& name) {
        ASSERT_FALSE(image.empty());
        std::filesystem::create_directories(FAULTLINE_UI_OUT_DIR);
        const std::string out = std::string(FAULTLINE_UI_OUT_DIR) + "/" + name + ".png";
        writePng(image, out);
        const std::string ref = std::string(FAULTLINE_UI_REF_DIR) + "/" + name + ".png";
        if (const char* update = std::getenv("FAULTLINE_UPDATE_REFS"); update && *update == '1') {
            writePng(image, ref);
            return;
        }
        ASSERT_TRUE(std::filesystem::exists(ref))
            << "no reference " << ref << " (see " << out << "; FAULTLINE_UPDATE_REFS=1 makes it)";
        const RgbaImage reference = readPng(ref);
        const double diff = meanAbsDiff(image, reference);
        EXPECT_LE(diff, kTolerance) << name << ": see " << out << " against " << ref;
        // And few pixels far off: a missing handle or edge moves the mean too little to see.
        const std::size_t far = differingPixels(image, reference);
        EXPECT_LE(far, kMaxDifferingPixels) << name << ": " << far << " pixels differ by more "
                                            << "than 48 of 255; see " << out << " against " << ref;
        // And the same structure (shading, edges, where things are) as a reader sees it.
        const double ssim = structuralSimilarity(image, reference);
        EXPECT_GE(ssim, kMinSsim) << name << ": SSIM " << ssim << "; see " << out << " against "
                                  << ref;
    }
};

RenderSettings small(int w = 400, int h = 300) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.supersample = 2;
    return s;
}

} // namespace

TEST_F(GlRender, TwoIntersectingSpheres) {
    // Two spheres overlapping by half a radius: the intersection must be a crisp curve, which
    // only exact per-pixel depth gives.
    core::Frame f;
    f.ids = {1, 2};
    f.x = {-0.55f, 0.55f};
    f.y = {0.0f, 0.3f};
    f.z = {0.0f, 0.0f};
    f.radius = {1.0f, 0.9f};
    f.attributes.push_back(core::makeAttribute("strain", {0.05f, 0.45f}, false));
    f.finalize();
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "strain";
    scene.colorMap = {core::ColorMapKind::BlueRed};
    scene.colorRange = core::ValueRange{0.0, 0.5};
    core::Camera cam;
    core::applyPreset(cam, core::ViewPreset::Front);
    core::orbitTurntable(cam, 0.35, 0.75);
    core::fitSphere(cam, {{0, 0.15, 0}, 1.7}, 4.0 / 3.0);
    scene.camera = cam;
    compareWithReference(renderSceneToImage(scene, small()), "two_spheres");
}

TEST_F(GlRender, ColourMappedLattice) {
    const core::Frame f = test::makeLattice(14, 10, 8);
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "strain";
    scene.colorMap = {core::ColorMapKind::Viridis};
    scene.colorRange = core::ValueRange{0.0, 0.5};
    compareWithReference(renderSceneToImage(scene, small()), "lattice_viridis");
}

// A lattice with a corner cut away by a box whose handles show, coloured in bands.
struct BoxCutScene {
    core::Frame frame = test::makeLattice(16, 12, 10);
    SceneDescription scene;
    explicit BoxCutScene(bool handles) {
        const core::CuttingBox cut{
            "corner", {7.5, -1, 4.5}, {16, 6.5, 10}, core::BoxMode::Cut, true};
        scene.frame = &frame;
        scene.visible.resize(frame.size());
        for (std::size_t i = 0; i < frame.size(); ++i)
            scene.visible[i] = !cut.contains(frame.x[i], frame.y[i], frame.z[i]);
        scene.colorVariable = "layer";
        scene.colorMap = *core::parseColorMap("bands:10");
        scene.boxes.push_back({{cut.min[0], cut.min[1], cut.min[2]},
                               {cut.max[0], cut.max[1], cut.max[2]},
                               {0.85f, 0.2f, 0.15f}});
        if (handles)
            scene.selectedBox = BoxHandlesOverlay{0, 0.0, core::BoxFace::MaxZ};
        scene.style.contextPoints = true;
    }
};

TEST_F(GlRender, BoxCutWithHandlesAndBands) {
    BoxCutScene s(true);
    compareWithReference(renderSceneToImage(s.scene, small()), "box_cut_bands");
}

TEST_F(GlRender, AMissingBoxHandleFailsTheComparison) {
    // The same figure without its handles: the mean over all bytes barely moves, the count of
    // pixels far off does.
    BoxCutScene s(false);
    const RgbaImage image = renderSceneToImage(s.scene, small());
    const RgbaImage reference = readPng(std::string(FAULTLINE_UI_REF_DIR) + "/box_cut_bands.png");
    const std::size_t far = differingPixels(image, reference);
    EXPECT_LE(meanAbsDiff(image, reference), kTolerance) << "the mean alone would catch it";
    EXPECT_GT(far, kMaxDifferingPixels);
}

TEST_F(GlRender, TransparentMeshThroughSpheres) {
    const core::Frame f = test::makeLattice(10, 8, 6);
    SceneDescription scene;
    scene.frame = &f;
    // A dipping plane through the block, coloured by height, half transparent.
    MeshData plane;
    const int n = 8;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -1.0f + 11.0f * float(i) / n, y = -1.0f + 9.0f * float(j) / n;
            const float z = 0.8f * (x - 1.0f);
            plane.positions.insert(plane.positions.end(), {x, y, z});
            plane.normals.insert(plane.normals.end(), {-0.6247f, 0.0f, 0.7809f});
            plane.colors.insert(plane.colors.end(), {0.95f, 0.55f + 0.04f * z, 0.2f});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            plane.indices.insert(plane.indices.end(), {a, b, c, c, b, d});
        }
    plane.opacity = 0.6f;
    scene.meshes.push_back(plane);
    scene.style.sphereColor = {0.72f, 0.74f, 0.78f};
    compareWithReference(renderSceneToImage(scene, small()), "mesh_and_spheres");
}

TEST_F(GlRender, OcclusionCullingDoesNotChangeTheImage) {
    // Enough spheres (> 20,000) for culling to run, viewed obliquely so pores show depth. The
    // spheres do not touch: where two touch, equal depths make the draw order pick the pixel.
    const core::Frame f = test::makeLattice(40, 30, 20, 0.47f);
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "strain";
    RenderSettings s = small(480, 320);
    s.supersample = 1;
    scene.style.culling = OcclusionCulling::Off;
    const RgbaImage plain = renderSceneToImage(scene, s);
    scene.style.culling = OcclusionCulling::On;
    auto renderer = std::make_unique<GlRenderer>();
    loadScene(*renderer, scene);
    renderer->render(fittedCamera(scene, 480, 320), {480, 320, 1, false});
    const RgbaImage culled = renderer->readImage();
    EXPECT_GT(renderer->stats().occlusionCulled, f.size() / 2); // it did cull
    EXPECT_EQ(renderer->stats().drawnSpheres + renderer->stats().occlusionCulled +
                  renderer->stats().frustumCulled,
              f.size());
    EXPECT_EQ(meanAbsDiff(plain, culled), 0.0);
}

// A view whose cell changes size keeps its texture's name: the workbench's draw list, built
// before the views render, still names it (a new texture per size left the draw list naming a
// deleted one: GL_INVALID_OPERATION and a blank view for a frame whenever a toolbar wrapped or a
// splitter moved).
TEST_F(GlRender, AResizedViewKeepsItsTexture) {
    core::Frame f;
    f.ids = {1, 2};
    f.x = {0, 1.5f};
    f.y = {0, 0};
    f.z = {0, 0};
    f.radius = {1, 1};
    f.finalize();
    SceneDescription scene;
    scene.frame = &f;
    auto renderer = std::make_unique<GlRenderer>();
    loadScene(*renderer, scene);
    renderer->render(fittedCamera(scene, 160, 120), {160, 120, 2, false});
    const unsigned int texture = renderer->colorTexture();
    ASSERT_NE(texture, 0u);
    renderer->render(fittedCamera(scene, 200, 90), {200, 90, 2, false});
    EXPECT_EQ(renderer->colorTexture(), texture);
    EXPECT_EQ(renderer->readImage().width, 200);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlRender, TransparentBackgroundKeepsAlpha) {
    core::Frame f;
    f.ids = {1};
    f.x = {0};
    f.y = {0};
    f.z = {0};
    f.radius = {1};
    f.finalize();
    SceneDescription scene;
    scene.frame = &f;
    RenderSettings s = small(64, 64);
    s.transparent = true;
    const RgbaImage img = renderSceneToImage(scene, s);
    EXPECT_EQ(img.at(0, 0)[3], 0);     // corner: background
    EXPECT_EQ(img.at(32, 32)[3], 255); // centre: the sphere
    EXPECT_GT(img.at(32, 32)[0], 40);
}

TEST_F(GlRender, LargeFigureSize) {
    // 3840 x 2160 works (without supersampling, to keep the test quick).
    const core::Frame f = test::makeLattice(6, 6, 6);
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "height";
    RenderSettings s = small(3840, 2160);
    s.supersample = 1;
    const RgbaImage img = renderSceneToImage(scene, s);
    EXPECT_EQ(img.width, 3840);
    EXPECT_EQ(img.height, 2160);
}

TEST_F(GlRender, SphereCoversItsExactDisc) {
    // One sphere of radius 1 seen from above: its disc must cover pi r^2 pixels, orthographic
    // (r = 25 pixels) and perspective (r = d tan-projected), within antialiasing at the rim.
    core::Frame f;
    f.ids = {1};
    f.x = {0};
    f.y = {0};
    f.z = {0};
    f.radius = {1};
    f.finalize();
    SceneDescription scene;
    scene.frame = &f;
    scene.style.ambientOcclusion = false;
    RenderSettings s = small(100, 100);
    s.transparent = true;
    s.supersample = 1;
    for (core::Projection proj : {core::Projection::Orthographic, core::Projection::Perspective}) {
        core::Camera cam;
        core::applyPreset(cam, core::ViewPreset::Top);
        cam.projection = proj;
        cam.fovYDegrees = 40.0;
        cam.distance = 2.0 / std::tan(20.0 * M_PI / 180.0); // view height 4 at the target
        scene.camera = cam;
        const RgbaImage img = renderSceneToImage(scene, s);
        int covered = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                covered += img.at(x, y)[3] > 127;
        // Perspective: the silhouette is where rays touch the sphere, radius d/sqrt(d^2-1)
        // times the scale at the target plane.
        const double d = cam.distance;
        const double rPx =
            proj == core::Projection::Orthographic ? 25.0 : 25.0 * d / std::sqrt(d * d - 1.0);
        EXPECT_NEAR(covered, M_PI * rPx * rPx, 2.0 * M_PI * rPx) << int(proj);
    }
}

namespace {

core::Frame spheresAt(const std::vector<glm::vec4>& spheres) {
    core::Frame f;
    std::vector<float> index;
    for (const glm::vec4& s : spheres) {
        f.ids.push_back(std::int64_t(f.ids.size()) + 1);
        f.x.push_back(s.x);
        f.y.push_back(s.y);
        f.z.push_back(s.z);
        f.radius.push_back(s.w);
        index.push_back(float(index.size()));
    }
    f.attributes.push_back(core::makeAttribute("index", std::move(index), false));
    f.finalize();
    return f;
}

core::Camera topCamera(glm::dvec3 target, double distance, double fovY = 40.0) {
    core::Camera cam;
    core::applyPreset(cam, core::ViewPreset::Top);
    cam.target = target;
    cam.distance = distance;
    cam.fovYDegrees = fovY;
    return cam;
}

int maxChannelDiff(const std::uint8_t* a, const std::uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 4; ++c)
        d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

} // namespace

TEST_F(GlRender, NearPlaneCutShowsAFlatDisc) {
    // A sphere of radius 1 under the eye (3 above its centre), a far one that puts the near
    // plane 2.02 from the eye (far / 10^4), so the plane cuts a cap of height 0.02 off the
    // first: a flat disc of radius 0.2 (13.7 px) inside the sphere's silhouette (48.6 px). A
    // third sphere wholly behind the eye must stay culled.
    const core::Frame f = spheresAt({{0, 0, 0, 1}, {0, 0, -20000, 1}, {0, 0, 5.5, 1}});
    SceneDescription scene;
    scene.frame = &f;
    scene.style.ambientOcclusion = false;
    scene.style.sphereColor = {0.8f, 0.6f, 0.4f};
    scene.camera = topCamera({0, 0, 0}, 3.0);
    RenderSettings s = small(100, 100);
    s.supersample = 1;
    s.transparent = true;
    const RgbaImage img = renderSceneToImage(scene, s);
    std::filesystem::create_directories(FAULTLINE_UI_OUT_DIR);
    writePng(img, std::string(FAULTLINE_UI_OUT_DIR) + "/near_cut_single.png");
    const std::uint8_t* centre = img.at(50, 50);
    // The disc: flat, the sphere's colour darkened, opaque.
    EXPECT_EQ(centre[3], 255);
    EXPECT_NEAR(centre[0], 0.8 * 0.72 * 255, 2);
    EXPECT_NEAR(centre[1], 0.6 * 0.72 * 255, 2);
    EXPECT_NEAR(centre[2], 0.4 * 0.72 * 255, 2);
    for (int dy = -9; dy <= 9; ++dy)
        for (int dx = -9; dx <= 9; ++dx)
            if (dx * dx + dy * dy <= 81) {
                ASSERT_LE(maxChannelDiff(img.at(50 + dx, 50 + dy), centre), 1) << dx << "," << dy;
            }
    // Around it the sphere's lit surface, beyond the near plane; outside it nothing.
    int surface = 0;
    for (int x = 68; x <= 94; ++x) {
        EXPECT_EQ(img.at(x, 50)[3], 255) << x;
        surface += maxChannelDiff(img.at(x, 50), centre) > 8;
    }
    EXPECT_GT(surface, 20);
    EXPECT_EQ(img.at(2, 2)[3], 0);
}

TEST_F(GlRender, EyeInsideASphereSeesItsCutFace) {
    // The eye half a radius from the centre: the near plane cuts the sphere in front of the eye
    // and the cut fills the view; nothing else is seen.
    const core::Frame f = spheresAt({{0, 0, 0, 1}, {0.3f, 0.2f, -3, 1}});
    SceneDescription scene;
    scene.frame = &f;
    scene.style.sphereColor = {0.5f, 0.7f, 0.9f};
    scene.camera = topCamera({0, 0, 0}, 0.5);
    RenderSettings s = small(64, 48);
    s.transparent = true;
    const RgbaImage img = renderSceneToImage(scene, s);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            ASSERT_LE(maxChannelDiff(img.at(x, y), img.at(0, 0)), 1) << x << "," << y;
    EXPECT_EQ(img.at(0, 0)[3], 255);
    EXPECT_NEAR(img.at(0, 0)[2], 0.9 * 0.72 * 255, 2);
}

TEST_F(GlRender, NearPlaneThroughSpheresOfAGrid) {
    // Spheres coloured by index at rising heights under a wide lens: the near plane (0.97 above
    // the middle) misses the three lowest and cuts the others ever lower (bigger discs).
    std::vector<glm::vec4> spheres;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            spheres.push_back(
                {2.1f * float(i - 1), 2.1f * float(j - 1), 0.12f * float(i + 3 * j) - 0.3f, 1});
    spheres.push_back({0, 0, -30000, 1});
    const core::Frame f = spheresAt(spheres);
    SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "index";
    scene.colorMap = {core::ColorMapKind::Viridis};
    scene.colorRange = core::ValueRange{0.0, 8.0};
    scene.style.showLegend = false;
    scene.camera = topCamera({0, 0, 0}, 4.0, 90.0);
    compareWithReference(renderSceneToImage(scene, small(200, 150)), "near_cut_grid");
}

namespace {

// A square of side 6 at height z centred on (cx, cy), split into n x n cells of two triangles.
MeshData square(float cx, float cy, float z, glm::vec3 color, int n = 6) {
    MeshData m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            m.positions.insert(m.positions.end(), {cx - 3 + 6.0f * float(i) / float(n),
                                                   cy - 3 + 6.0f * float(j) / float(n), z});
            m.normals.insert(m.normals.end(), {0, 0, 1});
            m.colors.insert(m.colors.end(), {color.r, color.g, color.b});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 1,
                       d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, c, b, d});
        }
    m.opacity = 0.55f;
    return m;
}

void reverseTriangles(MeshData& m) {
    std::vector<std::uint32_t> out;
    for (std::size_t t = m.indices.size() / 3; t-- > 0;)
        out.insert(out.end(), m.indices.begin() + 3 * t, m.indices.begin() + 3 * t + 3);
    m.indices = out;
}

} // namespace

TEST_F(GlRender, TransparentSurfacesBlendInDepthOrder) {
    // A red surface above a blue one, half overlapping, over two spheres, seen from above at a
    // slant: where they overlap red (nearer) must dominate, whatever order the meshes and their
    // triangles come in (unsorted, the one drawn last would).
    const core::Frame f = spheresAt({{0, 0, -2, 1}, {2.5f, 1, -2, 0.8f}});
    SceneDescription scene;
    scene.frame = &f;
    scene.style.sphereColor = {0.7f, 0.72f, 0.75f};
    const MeshData red = square(-1, 0, 1, {0.9f, 0.15f, 0.1f});
    const MeshData blue = square(1, 0, 0, {0.1f, 0.25f, 0.9f});
    core::Camera cam = topCamera({0, 0, 0}, 14.0, 40.0);
    core::orbitTurntable(cam, 0.3, 0.25);
    scene.camera = cam;
    const RenderSettings s = small(160, 120);

    scene.meshes = {red, blue};
    const RgbaImage redFirst = renderSceneToImage(scene, s);
    scene.meshes = {blue, red};
    const RgbaImage blueFirst = renderSceneToImage(scene, s);
    for (MeshData& m : scene.meshes)
        reverseTriangles(m);
    const RgbaImage reversed = renderSceneToImage(scene, s);
    EXPECT_EQ(meanAbsDiff(redFirst, blueFirst), 0.0);
    EXPECT_EQ(meanAbsDiff(redFirst, reversed), 0.0);

    // A pixel of the overlap (over no sphere): red over blue over white.
    const std::uint8_t* overlap = redFirst.at(80, 60);
    EXPECT_GT(int(overlap[0]), int(overlap[2]) + 30);
    compareWithReference(redFirst, "transparent_overlap");
}

TEST_F(GlRender, TransparentTrianglesSortOnlyWhenTheViewMoves) {
    SceneDescription scene;
    scene.meshes = {square(0, 0, 0, {0.9f, 0.5f, 0.2f}), square(1, 1, 1, {0.2f, 0.5f, 0.9f})};
    GlRenderer renderer;
    loadScene(renderer, scene);
    core::Camera cam = topCamera({0, 0, 0}, 20.0);
    const RenderTarget target{64, 64, 1, false};
    renderer.render(cam, target);
    renderer.render(cam, target);
    EXPECT_EQ(renderer.stats().meshSorts, 1u);
    EXPECT_EQ(renderer.stats().meshTriangles, 144u);
    core::orbitTurntable(cam, 0.1, 0.0);
    renderer.render(cam, target);
    EXPECT_EQ(renderer.stats().meshSorts, 2u);
}

// Radii far larger than the centres' spacing (another unit): each sphere would cover the whole
// view (one blob, and seconds a frame). The renderer draws, culls and fits them scaled down by
// core::radiusDrawScale, so the scene's bounds are the lattice's, not 20 units beyond it.
TEST_F(GlRender, RadiiFarLargerThanTheSpacingAreDrawnScaledDown) {
    const core::Frame f = test::makeLattice(14, 14, 14, 20.0f); // spacing 1
    SceneDescription scene;
    scene.frame = &f;
    GlRenderer renderer;
    loadScene(renderer, scene);
    const core::BoundingSphere bounds = renderer.sceneBounds();
    const double halfDiagonal =
        0.5 * std::sqrt(3.0) * (double(f.centreMax()[0]) - f.centreMin()[0]);
    EXPECT_LT(bounds.radius, halfDiagonal + 2.0);
    EXPECT_GT(bounds.radius, halfDiagonal);
}
