#include "core/view/triangle_depth_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace faultline::core;

namespace {

// One small triangle per height in zs, each with its own three vertices.
void horizontalTriangles(const std::vector<float>& zs, std::vector<float>& positions,
                         std::vector<std::uint32_t>& indices) {
    for (float z : zs) {
        const auto base = static_cast<std::uint32_t>(positions.size() / 3);
        positions.insert(positions.end(), {0, 0, z, 1, 0, z, 0, 1, z});
        indices.insert(indices.end(), {base, base + 1, base + 2});
    }
}

std::vector<std::uint32_t> firstVertices(const TriangleDepthOrder& order) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < order.indices().size(); i += 3)
        out.push_back(order.indices()[i]);
    return out;
}

} // namespace

TEST(TriangleDepthOrder, FarthestFirstFromEitherSide) {
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    horizontalTriangles({0.0f, -5.0f, 3.0f}, positions, indices); // first vertices 0, 3, 6
    TriangleDepthOrder order;
    order.setTriangles(positions, indices);
    EXPECT_TRUE(order.update({0, 0, 10}, {0, 0, -1}, true));
    EXPECT_EQ(firstVertices(order), (std::vector<std::uint32_t>{3, 0, 6}));
    EXPECT_TRUE(order.update({0, 0, -10}, {0, 0, 1}, true));
    EXPECT_EQ(firstVertices(order), (std::vector<std::uint32_t>{6, 0, 3}));
    // Orthographic: along the view direction, wherever the eye is (depths of both signs).
    EXPECT_TRUE(order.update({0, 0, 1}, {0, 0, -1}, false));
    EXPECT_EQ(firstVertices(order), (std::vector<std::uint32_t>{3, 0, 6}));
}

TEST(TriangleDepthOrder, SortsOnlyWhenTheViewChanged) {
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    horizontalTriangles({0.0f, 1.0f}, positions, indices);
    TriangleDepthOrder order;
    order.setTriangles(positions, indices);
    EXPECT_TRUE(order.update({0, 0, 10}, {0, 0, -1}, true));
    EXPECT_FALSE(order.update({0, 0, 10}, {0, 0, -1}, true));
    EXPECT_FALSE(order.update({0, 0, 10}, {0, 1, 0}, true)); // turning in place: same distances
    EXPECT_TRUE(order.update({0, 0, 11}, {0, 0, -1}, true));
    EXPECT_TRUE(order.update({0, 0, 11}, {0, 0, -1}, false));  // projection changed
    EXPECT_FALSE(order.update({5, 5, 50}, {0, 0, -1}, false)); // orthographic pan or zoom
    EXPECT_EQ(order.sorts(), 3u);
    order.setTriangles(positions, indices); // new mesh: sorts again
    EXPECT_TRUE(order.update({5, 5, 50}, {0, 0, -1}, false));
}

TEST(TriangleDepthOrder, ManyTrianglesArePermutedFarthestFirst) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-100.0f, 100.0f);
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    const std::size_t n = 20000;
    std::vector<std::uint32_t> triangles(n);
    for (std::size_t t = 0; t < n; ++t) {
        triangles[t] = static_cast<std::uint32_t>(t);
        for (int k = 0; k < 3; ++k)
            positions.insert(positions.end(), {u(rng), u(rng), u(rng)});
    }
    std::shuffle(triangles.begin(), triangles.end(), rng); // vertices 3t, 3t + 1, 3t + 2 each
    for (std::uint32_t t : triangles)
        indices.insert(indices.end(), {3 * t, 3 * t + 1, 3 * t + 2});
    TriangleDepthOrder order;
    order.setTriangles(positions, indices);
    const glm::dvec3 eye(30.0, -250.0, 40.0);
    ASSERT_TRUE(order.update(eye, {0, 1, 0}, true));
    const auto& sorted = order.indices();
    ASSERT_EQ(sorted.size(), indices.size());
    auto distance2 = [&](std::size_t t) {
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                c[a] += positions[3 * sorted[3 * t + k] + a] / 3.0;
        const double dx = c[0] - eye.x, dy = c[1] - eye.y, dz = c[2] - eye.z;
        return dx * dx + dy * dy + dz * dz;
    };
    for (std::size_t t = 1; t < n; ++t)
        ASSERT_GE(distance2(t - 1) * (1 + 1e-5), distance2(t)) << t;
    // The same triangles, each kept whole (its three indices stay together).
    std::vector<std::uint32_t> a(indices), b(sorted);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
    for (std::size_t t = 0; t < n; ++t) {
        ASSERT_EQ(sorted[3 * t] % 3, 0u);
        ASSERT_EQ(sorted[3 * t + 1], sorted[3 * t] + 1);
        ASSERT_EQ(sorted[3 * t + 2], sorted[3 * t] + 2);
    }
}
