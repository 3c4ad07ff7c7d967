// SurfaceCache: same request never rebuilds, iso-only change re-meshes, other keys build.
#include "core/surface/surface_cache.hpp"

#include <gtest/gtest.h>

namespace fc = faultline::core;

namespace {
struct CacheSpheres {
    std::vector<float> x{0.0f, 0.9f}, y{0, 0}, z{0, 0}, r{0.5f, 0.5f}, rgb{};
    fc::SphereSet set() const { return {x, y, z, r, rgb}; }
};
} // namespace

TEST(SurfaceCache, BuildsOnceThenRemeshesOnlyForANewIso) {
    const CacheSpheres s;
    fc::SurfaceCache cache;
    fc::SurfaceParams params;
    params.iso = 2.0f;
    params.voxelSize = 0.1f;
    const std::vector<std::int64_t> ids{1, 2};
    const fc::SurfaceKey key{3, fc::hashMemberIds(ids), fc::fieldParamsHash(params)};
    int gathers = 0;
    auto gather = [&] {
        ++gathers;
        return s.set();
    };
    const auto a = cache.get(key, params, gather);
    const auto b = cache.get(key, params, gather);
    EXPECT_EQ(a.field, b.field);
    EXPECT_EQ(b.mesh.indices, a.mesh.indices);
    params.iso = 2.05f; // inside [2 / 1.05, 2 * 1.05]
    const auto c = cache.get(key, params, gather);
    EXPECT_EQ(c.field, a.field);
    EXPECT_NE(c.mesh.positions.size(), 0u);
    params.iso = 3.0f; // outside: a new field
    const auto d = cache.get(key, params, gather);
    EXPECT_NE(d.field, a.field);
    const fc::SurfaceKey otherFrame{4, key.members, key.params};
    params.iso = 2.0f;
    cache.get(otherFrame, params, gather);
    const auto counters = cache.counters();
    EXPECT_EQ(counters.builds, 3u);
    EXPECT_EQ(counters.hits, 1u);
    EXPECT_EQ(counters.remeshes, 1u);
    EXPECT_EQ(gathers, 3);
    EXPECT_TRUE(cache.find(otherFrame, 2.0f).field);
    EXPECT_FALSE(cache.find(otherFrame, 2.5f).field);
}

TEST(SurfaceCache, EvictsLeastRecentlyUsedOverBudget) {
    const CacheSpheres s;
    fc::SurfaceCache cache(1); // every new entry evicts the older ones
    fc::SurfaceParams params;
    params.iso = 2.0f;
    params.voxelSize = 0.1f;
    for (int frame = 0; frame < 3; ++frame)
        cache.get({frame, 1, fc::fieldParamsHash(params)}, params, [&] { return s.set(); });
    EXPECT_EQ(cache.counters().evictions, 2u);
    EXPECT_TRUE(cache.find({2, 1, fc::fieldParamsHash(params)}, 2.0f).field);
    EXPECT_FALSE(cache.find({0, 1, fc::fieldParamsHash(params)}, 2.0f).field);
}

TEST(SurfaceCache, MemberHashDependsOnTheMembers) {
    const std::vector<std::int64_t> a{1, 2, 3}, b{1, 2, 4}, c{1, 2};
    EXPECT_NE(fc::hashMemberIds(a), fc::hashMemberIds(b));
    EXPECT_NE(fc::hashMemberIds(a), fc::hashMemberIds(c));
    EXPECT_EQ(fc::hashMemberIds(a), fc::hashMemberIds(std::vector<std::int64_t>{1, 2, 3}));
}

// keepOnly (a journal's surface.build): the surface is kept whole and the result holds no mesh;
// a later get returns the kept mesh, the same as a build returned to its caller.
TEST(SurfaceCache, KeepOnlyKeepsTheMeshAndReturnsNone) {
    const CacheSpheres s;
    fc::SurfaceParams params;
    params.iso = 2.0f;
    params.voxelSize = 0.1f;
    const fc::SurfaceKey key{0, 1, fc::fieldParamsHash(params)};
    auto gather = [&] { return s.set(); };
    fc::SurfaceCache plain, kept;
    const auto expected = plain.get(key, params, gather);
    ASSERT_GT(expected.mesh.indices.size(), 0u);
    const auto built = kept.get(key, params, gather, nullptr, true);
    EXPECT_NE(built.field, nullptr);
    EXPECT_EQ(built.mesh.indices.size(), 0u);
    EXPECT_EQ(kept.memoryBytes(), plain.memoryBytes());
    const auto again = kept.get(key, params, gather, nullptr, true); // a hit: still no copy
    EXPECT_EQ(again.mesh.indices.size(), 0u);
    const auto read = kept.get(key, params, gather);
    EXPECT_EQ(read.mesh.indices, expected.mesh.indices);
    EXPECT_EQ(read.mesh.positions, expected.mesh.positions);
    // A re-mesh at another iso-value in range, kept the same way.
    params.iso = 2.05f;
    EXPECT_EQ(kept.get(key, params, gather, nullptr, true).mesh.indices.size(), 0u);
    EXPECT_EQ(kept.get(key, params, gather).mesh.indices,
              plain.get(key, params, gather).mesh.indices);
    EXPECT_EQ(kept.counters().builds, 1u);
    EXPECT_EQ(kept.counters().remeshes, 1u);
    EXPECT_EQ(kept.counters().hits, 3u);
}
