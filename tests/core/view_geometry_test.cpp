#include "core/view/box_handles.hpp"
#include "core/view/geometry.hpp"
#include "core/view/sphere_picker.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <random>

using namespace faultline::core;

TEST(ViewGeometry, RaySphere) {
    const Ray r{{0, 0, 10}, {0, 0, -1}};
    EXPECT_DOUBLE_EQ(*intersectSphere(r, {0, 0, 0}, 1.0), 9.0);
    EXPECT_FALSE(intersectSphere(r, {3, 0, 0}, 1.0));
    EXPECT_FALSE(intersectSphere(r, {0, 0, 20}, 1.0));           // behind
    EXPECT_DOUBLE_EQ(*intersectSphere(r, {0, 0, 10}, 1.0), 0.0); // inside
}

TEST(ViewGeometry, RayBoxEntersThroughAFace) {
    const Ray r{{-5, 0.5, 0.5}, {1, 0, 0}};
    const auto hit = intersectBox(r, {0, 0, 0}, {1, 1, 1});
    ASSERT_TRUE(hit);
    EXPECT_DOUBLE_EQ(hit->tEnter, 5.0);
    EXPECT_DOUBLE_EQ(hit->tExit, 6.0);
    EXPECT_EQ(hit->enterAxis, 0);
    EXPECT_FALSE(intersectBox({{-5, 2, 0.5}, {1, 0, 0}}, {0, 0, 0}, {1, 1, 1}));
}

TEST(ViewGeometry, BoundingSphereHonoursMask) {
    const std::vector<float> x{0, 10, 2}, y{0, 0, 0}, z{0, 0, 0}, r{1, 1, 1};
    const BoundingSphere all = boundingSphereOf(x, y, z, r);
    EXPECT_DOUBLE_EQ(all.centre.x, 5.0);
    EXPECT_DOUBLE_EQ(all.radius, 6.0);
    const std::vector<std::uint8_t> mask{1, 0, 1};
    const BoundingSphere some = boundingSphereOf(x, y, z, r, mask);
    EXPECT_DOUBLE_EQ(some.centre.x, 1.0);
    EXPECT_DOUBLE_EQ(some.radius, 2.0);
    const Aabb box = boundsOf(x, y, z, r, mask);
    ASSERT_TRUE(box.valid);
    EXPECT_EQ(box.lo, glm::dvec3(-1, -1, -1));
    EXPECT_EQ(box.hi, glm::dvec3(3, 1, 1));
    EXPECT_FALSE(boundsOf(x, y, z, r, std::vector<std::uint8_t>{0, 0, 0}).valid);
    const BoundingSphere e = enclose({{0, 0, 0}, 1}, {{4, 0, 0}, 1});
    EXPECT_DOUBLE_EQ(e.centre.x, 2.0);
    EXPECT_DOUBLE_EQ(e.radius, 3.0);
}

TEST(BoxHandles, HandlesSitOnFaceCentres) {
    const auto h = boxFaceHandles({0, 0, 0}, {2, 4, 6});
    EXPECT_EQ(h[1].face, BoxFace::MaxX);
    EXPECT_EQ(h[1].centre, glm::dvec3(2, 2, 3));
    EXPECT_EQ(h[4].centre, glm::dvec3(1, 2, 0));
    EXPECT_EQ(h[4].normal, glm::dvec3(0, 0, -1));
    EXPECT_NEAR(defaultHandleRadius({0, 0, 0}, {2, 4, 6}), 0.04 * std::sqrt(56.0), 1e-12);
    EXPECT_DOUBLE_EQ(defaultHandleRadius({0, 0, 0}, {30, 30, 0.3}), 0.1);
}

TEST(BoxHandles, PickPrefersHandlesThenFaces) {
    const glm::dvec3 lo(0, 0, 0), hi(10, 10, 10);
    // Straight at the top handle from above.
    EXPECT_EQ(*pickBoxFace(lo, hi, {{5, 5, 20}, {0, 0, -1}}, 0.5), BoxFace::MaxZ);
    // From the west, off the handle: the face it enters through.
    EXPECT_EQ(*pickBoxFace(lo, hi, {{-20, 2, 8}, {1, 0, 0}}, 0.5), BoxFace::MinX);
    // The east handle sticks out beyond the box: a ray grazing past the box still grabs it.
    EXPECT_EQ(*pickBoxFace(lo, hi, {{10.3, -20, 5}, {0, 1, 0}}, 0.5), BoxFace::MaxX);
    EXPECT_FALSE(pickBoxFace(lo, hi, {{20, 20, 20}, {0, 0, 1}}, 0.5));
}

TEST(BoxHandles, DragMovesOneFaceAlongItsAxis) {
    const glm::dvec3 lo(0, 0, 0), hi(10, 10, 10);
    // Looking north at the box; drag the east face 3 units east (rays parallel to y).
    const Ray start{{10, -50, 5}, {0, 1, 0}};
    const Ray now{{13, -50, 5}, {0, 1, 0}};
    const BoxBounds moved = dragBoxFace(lo, hi, BoxFace::MaxX, start, now);
    EXPECT_DOUBLE_EQ(moved.hi.x, 13.0);
    EXPECT_EQ(moved.lo, lo);
    EXPECT_DOUBLE_EQ(moved.hi.y, 10.0);
    // Dragging the west face past the east face stops minSize short.
    const Ray far{{40, -50, 5}, {0, 1, 0}};
    const BoxBounds clamped =
        dragBoxFace(lo, hi, BoxFace::MinX, {{0, -50, 5}, {0, 1, 0}}, far, 1.0);
    EXPECT_DOUBLE_EQ(clamped.lo.x, 9.0);
    // A ray along the axis cannot drag.
    const BoxBounds same =
        dragBoxFace(lo, hi, BoxFace::MaxX, {{50, 5, 5}, {-1, 0, 0}}, {{50, 5, 5}, {-1, 0, 0}});
    EXPECT_EQ(same.hi, hi);
}

TEST(SpherePicker, NearestVisibleSphereAlongTheRay) {
    // A row of spheres along x; the ray runs along +x from the west.
    std::vector<float> x, y, z, r;
    for (int i = 0; i < 10; ++i) {
        x.push_back(float(i) * 2.0f);
        y.push_back(0);
        z.push_back(0);
        r.push_back(0.5f);
    }
    SpherePicker picker;
    picker.build(x, y, z, r);
    const Ray ray{{-10, 0, 0}, {1, 0, 0}};
    auto hit = picker.pick(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->row, 0u);
    EXPECT_DOUBLE_EQ(hit->t, 9.5);
    // Hide the first three.
    std::vector<std::uint8_t> mask(10, 1);
    mask[0] = mask[1] = mask[2] = 0;
    picker.build(x, y, z, r, mask);
    EXPECT_EQ(picker.indexedCount(), 7u);
    hit = picker.pick(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->row, 3u);
    EXPECT_FALSE(picker.pick({{-10, 3, 0}, {1, 0, 0}}));
    EXPECT_FALSE(picker.pick({{-10, 0, 0}, {-1, 0, 0}}));
}

TEST(SpherePicker, AgreesWithBruteForce) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-10, 10), rad(0.2f, 1.5f);
    std::vector<float> x, y, z, r;
    for (int i = 0; i < 3000; ++i) {
        x.push_back(pos(rng));
        y.push_back(pos(rng));
        z.push_back(pos(rng));
        r.push_back(rad(rng));
    }
    std::vector<std::uint8_t> mask(x.size());
    for (auto& m : mask)
        m = rng() % 3 != 0;
    SpherePicker picker;
    picker.build(x, y, z, r, mask);
    std::uniform_real_distribution<double> dir(-1, 1);
    for (int k = 0; k < 200; ++k) {
        Ray ray{{dir(rng) * 30, dir(rng) * 30, dir(rng) * 30}, {0, 0, 0}};
        ray.direction = glm::normalize(glm::dvec3(-ray.origin) +
                                       glm::dvec3(dir(rng), dir(rng), dir(rng)) * 5.0);
        std::optional<SphereHit> expect;
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (!mask[i])
                continue;
            auto t = intersectSphere(ray, {x[i], y[i], z[i]}, r[i]);
            if (t && (!expect || *t < expect->t))
                expect = SphereHit{i, *t, ray.at(*t)};
        }
        const auto got = picker.pick(ray);
        ASSERT_EQ(bool(got), bool(expect)) << "ray " << k;
        if (got) {
            EXPECT_EQ(got->row, expect->row) << "ray " << k;
            EXPECT_DOUBLE_EQ(got->t, expect->t);
        }
    }
}

// Issue 27: handles keep one size on screen (a share of the view's height at the camera's
// distance) instead of growing when zoomed in; opposite handles of a thin box never merge.
TEST(BoxHandles, ScreenRadiusFollowsTheZoomAndStaysApartOnThinBoxes) {
    const glm::dvec3 lo(0, 0, 0), hi(10, 10, 10);
    const double far = faultline::core::screenHandleRadius(lo, hi, 100.0, 35.0);
    const double near = faultline::core::screenHandleRadius(lo, hi, 25.0, 35.0);
    EXPECT_NEAR(near, far / 4.0, 1e-12);
    EXPECT_NEAR(far, faultline::core::kHandleScreenShare * 2 * 100.0 * std::tan(17.5 * M_PI / 180),
                1e-12);
    const glm::dvec3 thin(10, 10, 0.3);
    EXPECT_LE(faultline::core::screenHandleRadius(lo, thin, 1000.0, 35.0), 0.1 + 1e-12);
    EXPECT_GT(faultline::core::screenHandleRadius(lo, hi, 0.0, 35.0), 0.0); // unset: a fallback
}
