#include "core/view/occlusion_culling.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace faultline::core;

namespace {

// 64 x 64 pixels, 90 degree field of view, looking down -z from the origin.
SphereProjection makeProjection() {
    SphereProjection p;
    p.view = glm::dmat4(1.0);
    p.projection = glm::perspective(M_PI / 2, 1.0, 1.0, 100.0);
    p.width = 64;
    p.height = 64;
    p.perspective = true;
    return p;
}

double depthAt(const SphereProjection& p, double z) {
    const double clipZ = p.projection[2][2] * z + p.projection[3][2];
    return 0.5 * clipZ / -z + 0.5;
}

} // namespace

TEST(OcclusionCulling, FootprintCoversTheProjectedDisc) {
    const SphereProjection p = makeProjection();
    SphereFootprint f;
    ASSERT_TRUE(projectSphere(p, {0, 0, -10}, 1.0, f));
    // The disc spans 32 +- 32 / sqrt(99) = 32 +- 3.2 pixels.
    EXPECT_LE(f.x0, 28);
    EXPECT_GE(f.x1, 35);
    EXPECT_GE(f.x0, 26);
    EXPECT_LE(f.x1, 37);
    EXPECT_EQ(f.x0, f.y0);
    EXPECT_EQ(f.x1, f.y1);
    EXPECT_NEAR(f.nearDepth, depthAt(p, -9.0), 2e-6);
    EXPECT_FALSE(f.crossesNear);
    // Off to the side, behind the eye, beyond the far plane.
    EXPECT_FALSE(projectSphere(p, {50, 0, -10}, 1.0, f));
    EXPECT_FALSE(projectSphere(p, {0, 0, 10}, 1.0, f));
    EXPECT_FALSE(projectSphere(p, {0, 0, -200}, 1.0, f));
    // Poking through the near plane: the whole screen, never culled.
    ASSERT_TRUE(projectSphere(p, {0, 0, -1.5}, 1.0, f));
    EXPECT_TRUE(f.crossesNear);
    EXPECT_EQ(f.x0, 0);
    EXPECT_EQ(f.x1, 63);
}

TEST(OcclusionCulling, OffCentreFootprintIsExact) {
    // A sphere far off-axis: its projection is an ellipse stretched outwards; the footprint must
    // still contain it. Check by sampling the sphere's silhouette directions.
    const SphereProjection p = makeProjection();
    const glm::dvec3 c(7, -5, -9);
    const double r = 2.0;
    SphereFootprint f;
    ASSERT_TRUE(projectSphere(p, c, r, f));
    for (int i = 0; i < 2000; ++i) {
        const double u = std::acos(1 - 2 * (i + 0.5) / 2000.0), v = i * 2.399963;
        const glm::dvec3 q =
            c + r * glm::dvec3(std::sin(u) * std::cos(v), std::sin(u) * std::sin(v), std::cos(u));
        const double px = (q.x / -q.z * 0.5 + 0.5) * 64, py = (q.y / -q.z * 0.5 + 0.5) * 64;
        if (px < 0 || px >= 64 || py < 0 || py >= 64)
            continue;
        EXPECT_GE(px, f.x0);
        EXPECT_LE(px, f.x1 + 1);
        EXPECT_GE(py, f.y0);
        EXPECT_LE(py, f.y1 + 1);
    }
}

TEST(OcclusionCulling, CullsOnlyWhatIsWhollyBehind) {
    const SphereProjection p = makeProjection();
    const std::vector<float> x{0, 0, 20, -200}, y{0, 0, 0, 0}, z{-10, -10, -30, -10}, r{1, 1, 1, 1};
    const std::vector<std::uint32_t> rows{0, 1, 2, 3};
    SphereOcclusionCuller culler;
    culler.begin(x, y, z, r, rows, p);
    EXPECT_EQ(culler.frustumCulled(), 1u); // row 3 is off-screen
    EXPECT_EQ(culler.candidateCount(), 3u);

    // Everything drawn so far is at z = -5: rows 0..2 are all behind it.
    std::vector<float> depth(64 * 64, float(depthAt(p, -5.0)));
    culler.cullBehind(depth);
    EXPECT_EQ(culler.candidateCount(), 0u);
    EXPECT_EQ(culler.occlusionCulled(), 3u);

    // A one-pixel hole of background inside row 0's footprint keeps rows 0 and 1.
    culler.begin(x, y, z, r, rows, p);
    depth[32 * 64 + 32] = 1.0f;
    culler.cullBehind(depth);
    EXPECT_EQ(culler.takeRemaining(), (std::vector<std::uint32_t>{0, 1}));

    // A hole elsewhere does not.
    culler.begin(x, y, z, r, rows, p);
    depth[32 * 64 + 32] = float(depthAt(p, -5.0));
    depth[2 * 64 + 2] = 1.0f;
    culler.cullBehind(depth);
    EXPECT_EQ(culler.candidateCount(), 0u);

    // Rows 0 and 1 reach nearer than the depth buffer (their front is at -9): kept.
    culler.begin(x, y, z, r, rows, p);
    std::fill(depth.begin(), depth.end(), float(depthAt(p, -9.5)));
    culler.cullBehind(depth);
    EXPECT_EQ(culler.takeRemaining(), (std::vector<std::uint32_t>{0, 1}));
}

TEST(OcclusionCulling, OccludersAreTheNearestPerTile) {
    const SphereProjection p = makeProjection();
    // Rows 0 and 1 on the same line of sight; row 1 nearer. Row 2 elsewhere.
    const std::vector<float> x{0, 0, 20}, y{0, 0, 0}, z{-10, -6, -30}, r{1, 0.6f, 1};
    const std::vector<std::uint32_t> rows{0, 1, 2};
    SphereOcclusionCuller culler;
    culler.begin(x, y, z, r, rows, p);
    std::vector<std::uint32_t> occluders = culler.takeOccluders(8);
    std::sort(occluders.begin(), occluders.end());
    EXPECT_EQ(occluders, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_EQ(culler.candidateCount(), 1u);
    EXPECT_EQ(culler.takeRemaining(), (std::vector<std::uint32_t>{0}));
}

TEST(OcclusionCulling, OrthographicFootprint) {
    SphereProjection p;
    p.projection = glm::ortho(-8.0, 8.0, -8.0, 8.0, 0.0, 100.0);
    p.width = p.height = 64;
    p.perspective = false;
    SphereFootprint f;
    ASSERT_TRUE(projectSphere(p, {0, 0, -10}, 2.0, f)); // 2 units = 8 pixels
    EXPECT_EQ(f.x0, 22);
    EXPECT_EQ(f.x1, 41);
}
