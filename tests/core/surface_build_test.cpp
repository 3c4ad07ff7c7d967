// Fault surfaces end to end: mesh geometry, normals, colours, re-meshing, refusals, cancel.
#include "core/surface/fault_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace fc = faultline::core;

namespace {

struct Spheres {
    std::vector<float> x, y, z, r, rgb;
    fc::SphereSet set() const { return {x, y, z, r, rgb}; }
};

Spheres single(float radius, std::array<float, 3> colour) {
    return {{0.1f}, {-0.2f}, {0.3f}, {radius}, {colour[0], colour[1], colour[2]}};
}

double distanceFromCentre(const std::array<float, 3>& p) {
    return std::sqrt((p[0] - 0.1) * (p[0] - 0.1) + (p[1] + 0.2) * (p[1] + 0.2) +
                     (p[2] - 0.3) * (p[2] - 0.3));
}

class CancelAfter : public fc::Interrupter {
  public:
    bool wasInterrupted(int) override { return ++m_calls > 2; }
    std::atomic<int> m_calls{0};
};

} // namespace

TEST(FaultSurface, SingleSphereInverseSquareIsASphereOfRadiusSqrtROverIso) {
    const Spheres s = single(0.5f, {0.2f, 0.4f, 0.6f});
    fc::SurfaceParams params;
    params.iso = 1.0f;
    params.voxelSize = 0.05f;
    params.colorReach = 0.5f; // the surface at 0.707 lies within radius + reach = 1.0
    const auto result = fc::buildSurface(s.set(), params);
    const auto& mesh = result.mesh;
    ASSERT_GT(mesh.triangleCount(), 100u);
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const auto& p = mesh.positions[i];
        EXPECT_NEAR(distanceFromCentre(p), std::sqrt(0.5), 2e-3);
        const double d = distanceFromCentre(p);
        const std::array<double, 3> radial{(p[0] - 0.1) / d, (p[1] + 0.2) / d, (p[2] - 0.3) / d};
        const auto& n = mesh.normals[i];
        EXPECT_GT(n[0] * radial[0] + n[1] * radial[1] + n[2] * radial[2], 0.999);
        EXPECT_NEAR(mesh.colors[i][0], 0.2f, 1e-5f);
        EXPECT_NEAR(mesh.colors[i][2], 0.6f, 1e-5f);
    }
    // Counter-clockwise seen from outside.
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const auto& a = mesh.positions[mesh.indices[t]];
        const auto& b = mesh.positions[mesh.indices[t + 1]];
        const auto& c = mesh.positions[mesh.indices[t + 2]];
        const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const std::array<double, 3> v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const std::array<double, 3> n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                      u[0] * v[1] - u[1] * v[0]};
        EXPECT_GT(n[0] * (a[0] - 0.1) + n[1] * (a[1] + 0.2) + n[2] * (a[2] - 0.3), 0.0);
    }
}

TEST(FaultSurface, InitialColourWhereNoSphereReaches) {
    const Spheres s = single(0.5f, {0.2f, 0.4f, 0.6f});
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Inverse; // surface at d = r / iso = 0.5 / 0.8
    params.iso = 0.8f;
    params.voxelSize = 0.05f;
    params.initialColor = {0.9f, 0.1f, 0.1f};
    const auto result = fc::buildSurface(s.set(), params);
    ASSERT_FALSE(result.mesh.positions.empty());
    for (std::size_t i = 0; i < result.mesh.positions.size(); ++i) {
        EXPECT_NEAR(distanceFromCentre(result.mesh.positions[i]), 0.625, 2e-3);
        EXPECT_NEAR(result.mesh.colors[i][0], 0.9f, 1e-5f);
        EXPECT_NEAR(result.mesh.colors[i][1], 0.1f, 1e-5f);
    }
}

TEST(FaultSurface, RemeshWithinTheRangeNeedsNoNewField) {
    const Spheres s = single(0.5f, {1, 1, 1});
    fc::SurfaceParams params;
    params.kernel = fc::MetaballKernel::Inverse;
    params.iso = 1.0f;
    params.voxelSize = 0.05f;
    params.isoRangeFactor = 1.5f;
    const auto result = fc::buildSurface(s.set(), params);
    EXPECT_FLOAT_EQ(result.field->isoMin(), 1.0f / 1.5f);
    const auto mesh = fc::remesh(*result.field, 1.25f);
    ASSERT_FALSE(mesh.positions.empty());
    // Marching cubes interpolates linearly along edges: 1/d bends by ~h^2 f'' / 8 f' there.
    for (const auto& p : mesh.positions)
        EXPECT_NEAR(distanceFromCentre(p), 0.4, 3e-3);
    EXPECT_THROW(fc::remesh(*result.field, 3.0f), fc::SurfaceRequestError);
    // Grid normals (central differences of the stored field) agree with the analytic ones.
    const auto fast = fc::remesh(*result.field, 1.25f, nullptr, fc::NormalSource::Grid);
    ASSERT_EQ(fast.normals.size(), mesh.normals.size());
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
        const auto& a = mesh.normals[i];
        const auto& b = fast.normals[i];
        EXPECT_GT(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], 0.999);
    }
}

// Leaves are meshed separately; where they meet, every edge of the mesh must still be shared by
// a triangle on each side, wound the other way (no holes, no flipped patches), at the build's
// iso and at re-meshed ones, for the long-tailed and the compact kernel.
TEST(FaultSurface, MeshesAreClosedAcrossLeavesAndWoundOutwards) {
    Spheres s;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> at(0.0f, 4.0f), radius(0.3f, 0.6f);
    for (int n = 0; n < 60; ++n) {
        s.x.push_back(at(random));
        s.y.push_back(at(random) * 0.5f);
        s.z.push_back(at(random));
        s.r.push_back(radius(random));
        s.rgb.insert(s.rgb.end(), {0.2f, 0.4f, 0.8f});
    }
    for (auto kernel : {fc::MetaballKernel::InverseSquare, fc::MetaballKernel::Compact}) {
        fc::SurfaceParams params;
        params.kernel = kernel;
        params.iso = kernel == fc::MetaballKernel::Compact ? 0.3f : 12.0f;
        params.voxelSize = 0.09f;
        params.isoRangeFactor = 1.2f;
        const auto built = fc::buildSurface(s.set(), params);
        for (float iso : {params.iso, params.iso * 1.15f, params.iso / 1.15f}) {
            const auto mesh = fc::remesh(*built.field, iso);
            ASSERT_GT(mesh.triangleCount(), 1000u);
            std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
                for (int e = 0; e < 3; ++e)
                    ++directed[{mesh.indices[t + e], mesh.indices[t + (e + 1) % 3]}];
            std::size_t open = 0;
            for (const auto& [edge, count] : directed) {
                const auto back = directed.find({edge.second, edge.first});
                open += back == directed.end() || back->second != count;
            }
            EXPECT_EQ(open, 0u) << fc::kernelName(kernel) << " at iso " << iso;
            // Counter-clockwise from outside: the face normal agrees with the vertex normals.
            std::size_t agree = 0;
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
                const auto& a = mesh.positions[mesh.indices[t]];
                const auto& b = mesh.positions[mesh.indices[t + 1]];
                const auto& c = mesh.positions[mesh.indices[t + 2]];
                const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                const float v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                const float face[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                       u[0] * v[1] - u[1] * v[0]};
                const auto& n = mesh.normals[mesh.indices[t]];
                agree += face[0] * n[0] + face[1] * n[1] + face[2] * n[2] > 0.0f;
            }
            EXPECT_GT(double(agree), 0.99 * double(mesh.triangleCount()));
        }
    }
}

TEST(FaultSurface, RefusesBadRequestsBeforeWork) {
    fc::SurfaceParams params;
    EXPECT_THROW(fc::buildSurface(fc::SphereSet{}, params), fc::SurfaceRequestError);
    const Spheres s = single(0.5f, {1, 1, 1});
    params.iso = -1.0f;
    EXPECT_THROW(fc::buildSurface(s.set(), params), fc::SurfaceRequestError);
    params.iso = 1.0f;
    params.voxelSize = 1e-4f;
    params.memoryBudgetBytes = std::size_t{256} << 20;
    try {
        fc::buildSurface(s.set(), params);
        FAIL() << "expected a refusal";
    } catch (const fc::SurfaceRequestError& e) {
        EXPECT_NE(std::string(e.what()).find("budget is 256.0 MiB"), std::string::npos) << e.what();
    }
}

TEST(FaultSurface, CancelStopsTheBuild) {
    Spheres s;
    for (int i = 0; i < 400; ++i) {
        s.x.push_back(float(i % 20));
        s.y.push_back(float(i / 20));
        s.z.push_back(0.0f);
        s.r.push_back(0.5f);
    }
    fc::SurfaceParams params;
    params.iso = 3.0f;
    CancelAfter cancel;
    EXPECT_THROW(fc::buildSurface(s.set(), params, &cancel), fc::SurfaceCancelled);
}
