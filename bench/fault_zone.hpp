// Synthetic fault zones for the surface benchmarks: spheres of an HCP lattice (touching, radius
// r) kept within a slab around a dipping plane, coloured by their depth across the zone.
#pragma once

#include "core/surface/sphere_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace faultline::bench {

struct FaultZone {
    std::vector<float> x, y, z, radius, rgb;
    core::SphereSet set() const { return {x, y, z, radius, rgb}; }
};

// `count` spheres of radius r in a square zone `thickness` thick, dipping 60 degrees to the north.
inline FaultZone hcpFaultZone(std::size_t count, float r, float thickness) {
    const double dip = 60.0 * 3.14159265358979 / 180.0;
    const double n[3] = {0.0, std::sin(dip), std::cos(dip)};  // plane normal
    const double u[3] = {1.0, 0.0, 0.0};                      // strike
    const double v[3] = {0.0, std::cos(dip), -std::sin(dip)}; // down dip
    const double density = 0.7405 / (4.0 / 3.0 * 3.14159265358979 * r * r * r);
    const double side = std::sqrt(1.15 * count / (density * thickness));
    const double reach = side / 2 + thickness;
    const int ni = static_cast<int>(reach / (2 * r)) + 2;
    const int nj = static_cast<int>(reach / (std::sqrt(3.0) * r)) + 2;
    const int nk = static_cast<int>(reach / (2 * std::sqrt(6.0) / 3 * r)) + 2;
    struct Candidate {
        double p[3];
        double key;
    };
    std::vector<Candidate> kept;
    for (int k = -nk; k <= nk; ++k)
        for (int j = -nj; j <= nj; ++j)
            for (int i = -ni; i <= ni; ++i) {
                const int kk = ((k % 2) + 2) % 2;
                const double p[3] = {(2.0 * i + (((j + k) % 2 + 2) % 2)) * r,
                                     std::sqrt(3.0) * (j + kk / 3.0) * r,
                                     2.0 * std::sqrt(6.0) / 3.0 * k * r};
                const double across = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
                if (std::abs(across) > thickness / 2)
                    continue;
                const double a = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
                const double b = p[0] * v[0] + p[1] * v[1] + p[2] * v[2];
                kept.push_back({{p[0], p[1], p[2]}, std::max(std::abs(a), std::abs(b))});
            }
    std::sort(kept.begin(), kept.end(),
              [](const Candidate& a, const Candidate& b) { return a.key < b.key; });
    kept.resize(std::min(kept.size(), count));
    FaultZone zone;
    for (const auto& c : kept) {
        zone.x.push_back(static_cast<float>(c.p[0]));
        zone.y.push_back(static_cast<float>(c.p[1]));
        zone.z.push_back(static_cast<float>(c.p[2]));
        zone.radius.push_back(r);
        const double across = (c.p[0] * n[0] + c.p[1] * n[1] + c.p[2] * n[2]) / thickness + 0.5;
        zone.rgb.insert(zone.rgb.end(),
                        {static_cast<float>(across), 0.3f, static_cast<float>(1.0 - across)});
    }
    return zone;
}

} // namespace faultline::bench

namespace faultline::bench {

// The faulted block of the spread-out benchmarks: a 200 x 130 x 110 block of touching spheres
// (HCP, radius 1) crossed by three planar fault zones with 60-degree dips (to the east, the
// west and the north). Calls f(p, across) for every sphere, with its signed distances to the
// three zones' mid-planes.
template <typename F> void forEachFaultedBlockSphere(F f) {
    constexpr double r = 1.0;
    constexpr double size[3] = {200.0, 130.0, 110.0};
    const double dip = 60.0 * 3.14159265358979 / 180.0;
    // Unit normals and a point on each plane.
    const double normals[3][3] = {{std::sin(dip), 0.0, std::cos(dip)},
                                  {-std::sin(dip), 0.0, std::cos(dip)},
                                  {0.0, std::sin(dip), std::cos(dip)}};
    const double points[3][3] = {{70.0, 65.0, 55.0}, {130.0, 65.0, 55.0}, {100.0, 65.0, 55.0}};
    const int nk = static_cast<int>(size[2] / (2 * std::sqrt(6.0) / 3 * r));
    const int nj = static_cast<int>(size[1] / (std::sqrt(3.0) * r));
    const int ni = static_cast<int>(size[0] / (2 * r));
    for (int k = 0; k < nk; ++k)
        for (int j = 0; j < nj; ++j)
            for (int i = 0; i < ni; ++i) {
                const int kk = k % 2;
                const double p[3] = {(2.0 * i + ((j + k) % 2)) * r + r,
                                     std::sqrt(3.0) * (j + kk / 3.0) * r + r,
                                     2.0 * std::sqrt(6.0) / 3.0 * k * r + r};
                double across[3];
                for (int z = 0; z < 3; ++z)
                    across[z] = (p[0] - points[z][0]) * normals[z][0] +
                                (p[1] - points[z][1]) * normals[z][1] +
                                (p[2] - points[z][2]) * normals[z][2];
                f(p, across);
            }
}

// What a user selects in a whole faulted block (issue 23): the high-strain spheres of
// forEachFaultedBlockSphere's three zones, 3 radii thick, thinned evenly to about `count` spheres
// as a strain threshold thins them. Spread out: the selection's bounding box is the whole block,
// and most of it is far from any sphere.
inline FaultZone spreadFaultZones(std::size_t count) {
    constexpr double r = 1.0, halfThickness = 1.5, height = 110.0;
    std::vector<std::array<double, 4>> members; // x, y, z, which zone
    forEachFaultedBlockSphere([&](const double* p, const double* across) {
        for (int f = 0; f < 3; ++f)
            if (std::abs(across[f]) <= halfThickness) {
                members.push_back({p[0], p[1], p[2], double(f)});
                break;
            }
    });
    // Thin evenly (a fixed hash of the index, so every run keeps the same spheres).
    const double keep = std::min(1.0, double(count) / double(members.size()));
    FaultZone zone;
    for (std::size_t m = 0; m < members.size(); ++m) {
        std::uint64_t h = (m + 1) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 31;
        h *= 0xBF58476D1CE4E5B9ull;
        h ^= h >> 29;
        if (double(h >> 11) / double(1ull << 53) >= keep)
            continue;
        const auto& c = members[m];
        zone.x.push_back(float(c[0]));
        zone.y.push_back(float(c[1]));
        zone.z.push_back(float(c[2]));
        zone.radius.push_back(float(r));
        const float t = float(c[2] / height);
        zone.rgb.insert(zone.rgb.end(), {t, float(c[3]) / 2.0f, 1.0f - t});
    }
    return zone;
}

} // namespace faultline::bench
