#include "core/view/camera.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace faultline::core;

namespace {
void expectVec(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
// Screen position (ndc) of a world point.
glm::dvec2 project(const Camera& c, const glm::dvec3& p, double aspect) {
    const glm::dmat4 m = projectionMatrix(c, aspect, {0.01, 1000}) * viewMatrix(c);
    const glm::dvec4 q = m * glm::dvec4(p, 1.0);
    return glm::dvec2(q) / q.w;
}
} // namespace

TEST(Camera, PresetsFollowEastNorthUp) {
    Camera c;
    applyPreset(c, ViewPreset::Front);
    expectVec(c.forward(), {0, 1, 0});
    expectVec(c.right(), {1, 0, 0});
    expectVec(c.up(), {0, 0, 1});
    applyPreset(c, ViewPreset::Side);
    expectVec(c.forward(), {-1, 0, 0});
    expectVec(c.right(), {0, 1, 0});
    applyPreset(c, ViewPreset::Top);
    expectVec(c.forward(), {0, 0, -1});
    expectVec(c.up(), {0, 1, 0});
    expectVec(c.right(), {1, 0, 0});
    applyPreset(c, ViewPreset::Iso);
    EXPECT_LT(c.forward().z, 0.0); // looking down
    EXPECT_GT(c.forward().y, 0.0); // towards the north
    EXPECT_NEAR(c.right().z, 0.0, 1e-12);
    EXPECT_EQ(*parseViewPreset("right"), ViewPreset::Side);
    EXPECT_EQ(*parseViewPreset("TOP"), ViewPreset::Top);
    EXPECT_FALSE(parseViewPreset("diagonal"));
}

TEST(Camera, ViewMatrixPutsTargetAheadOnAxis) {
    Camera c;
    c.target = {5, 6, 7};
    c.distance = 10;
    applyPreset(c, ViewPreset::Front);
    expectVec(c.eye(), {5, -4, 7});
    const glm::dvec4 t = viewMatrix(c) * glm::dvec4(c.target, 1.0);
    expectVec(glm::dvec3(t), {0, 0, -10});
    const glm::dvec2 east = project(c, {6, 6, 7}, 1.0);
    EXPECT_GT(east.x, 0.0);
    EXPECT_NEAR(east.y, 0.0, 1e-12);
}

TEST(Camera, FitSphereTouchesTheNarrowSide) {
    Camera c;
    c.fovYDegrees = 60;
    fitSphere(c, {{1, 2, 3}, 2.0}, 2.0, 1.0);
    expectVec(c.target, {1, 2, 3});
    EXPECT_NEAR(c.distance, 2.0 / std::sin(M_PI / 6), 1e-9); // vertical half-angle 30 degrees
    c.projection = Projection::Orthographic;
    fitSphere(c, {{0, 0, 0}, 2.0}, 0.5, 1.0); // tall view: width limits
    EXPECT_NEAR(c.viewHeightAtTarget() * 0.5 * 0.5, 2.0, 1e-9);
}

TEST(Camera, ClipRangeEnclosesTheScene) {
    Camera c;
    c.distance = 10;
    const ClipRange r = clipRangeFor(c, {{0, 0, 0}, 2.0});
    EXPECT_LT(r.nearClip, 8.0);
    EXPECT_GT(r.nearClip, 0.0);
    EXPECT_GT(r.farClip, 12.0);
    c.distance = 1; // eye inside the scene: near stays positive
    EXPECT_GT(clipRangeFor(c, {{0, 0, 0}, 2.0}).nearClip, 0.0);
    c.projection = Projection::Orthographic; // may reach behind the eye
    EXPECT_LT(clipRangeFor(c, {{0, 0, 0}, 2.0}).nearClip, 0.0);
}

TEST(Camera, ZoomToCursorKeepsThePointUnderTheCursor) {
    for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
        Camera c;
        c.projection = proj;
        c.distance = 20;
        applyPreset(c, ViewPreset::Iso);
        const double aspect = 1.5;
        const glm::dvec2 cursor(0.4, -0.3);
        // The point under the cursor on the target plane.
        const Ray ray = cameraRay(c, cursor, aspect);
        const double t =
            glm::dot(c.target - ray.origin, c.forward()) / glm::dot(ray.direction, c.forward());
        const glm::dvec3 p = ray.at(t);
        zoomToCursor(c, 2.0, cursor, aspect);
        EXPECT_NEAR(c.distance, 10.0, 1e-12);
        const glm::dvec2 after = project(c, p, aspect);
        EXPECT_NEAR(after.x, cursor.x, 1e-9);
        EXPECT_NEAR(after.y, cursor.y, 1e-9);
    }
}

TEST(Camera, PanMovesTheSceneWithTheCursor) {
    Camera c;
    c.distance = 10;
    applyPreset(c, ViewPreset::Front);
    const glm::dvec3 p(1, 0, 2);
    const glm::dvec2 before = project(c, p, 1.0);
    pan(c, {0.2, -0.1}, 1.0);
    const glm::dvec2 after = project(c, p, 1.0);
    // Points on the target plane follow the cursor exactly.
    EXPECT_NEAR(after.x - before.x, 0.2, 1e-9);
    EXPECT_NEAR(after.y - before.y, -0.1, 1e-9);
}

TEST(Camera, TrackballTurnsAboutTheTarget) {
    Camera c;
    c.target = {1, 1, 1};
    c.distance = 5;
    applyPreset(c, ViewPreset::Front);
    orbitTrackball(c, {0, 0}, {0.5, 0}, 1.0);
    EXPECT_NEAR(glm::length(c.eye() - c.target), 5.0, 1e-9);
    // Dragging right turns the scene right: the camera moves to the west (-x).
    EXPECT_LT(c.eye().x, 1.0);
    EXPECT_NEAR(glm::length(c.orientation), 1.0, 1e-12);
    // A drag and its reverse cancel.
    orbitTrackball(c, {0.5, 0}, {0, 0}, 1.0);
    expectVec(c.forward(), {0, 1, 0}, 1e-9);
}

TEST(Camera, TurntableKeepsZUpAndStopsAtThePoles) {
    Camera c;
    applyPreset(c, ViewPreset::Front);
    orbitTurntable(c, 0.3, 0.2);
    EXPECT_NEAR(c.right().z, 0.0, 1e-12);
    EXPECT_GT(c.up().z, 0.0);
    orbitTurntable(c, 0.0, 10.0); // far past straight down
    EXPECT_LT(c.forward().z, -0.99);
    EXPECT_GT(c.up().z, 0.0);
}

TEST(Camera, RaysGoThroughPixels) {
    Camera c;
    c.distance = 10;
    c.target = {0, 0, 0};
    applyPreset(c, ViewPreset::Top);
    const Ray centre = cameraRay(c, {0, 0}, 1.0);
    expectVec(centre.origin, {0, 0, 10});
    expectVec(centre.direction, {0, 0, -1});
    c.projection = Projection::Orthographic;
    const Ray off = cameraRay(c, {1, 0}, 2.0);
    expectVec(off.direction, {0, 0, -1});
    EXPECT_NEAR(off.origin.x, 0.5 * c.viewHeightAtTarget() * 2.0, 1e-9);
    EXPECT_GT(off.origin.z, 10.0);
}

TEST(Camera, FitBoxKeepsEveryCornerInViewAndOneOnTheEdge) {
    const Aabb box{{0, 0, 0}, {60, 35, 25}, true};
    for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
        for (ViewPreset preset : {ViewPreset::Iso, ViewPreset::Front, ViewPreset::Top}) {
            Camera c;
            c.projection = proj;
            applyPreset(c, preset);
            const double aspect = 16.0 / 9.0;
            fitBox(c, box, aspect, 1.0);
            EXPECT_EQ(c.target, glm::dvec3(30, 17.5, 12.5));
            double extreme = 0.0;
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 p(i & 1 ? 60 : 0, i & 2 ? 35 : 0, i & 4 ? 25 : 0);
                const glm::dvec2 q = project(c, p, aspect);
                EXPECT_LE(std::abs(q.x), 1.0 + 1e-9);
                EXPECT_LE(std::abs(q.y), 1.0 + 1e-9);
                extreme = std::max({extreme, std::abs(q.x), std::abs(q.y)});
            }
            EXPECT_NEAR(extreme, 1.0, 1e-9) << int(proj) << " " << int(preset);
        }
    }
}
