// Synthetic fault zones for the surface benchmarks: spheres of an HCP lattice (touching, radius
// r) kept within a slab around a dipping plane, coloured by their depth across the zone.
#pragma once

#include "core/surface/sphere_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
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
              [](const Candidate &a, const Candidate &b) { return a.key < b.key; });
    kept.resize(std::min(kept.size(), count));
    FaultZone zone;
    for (const auto &c : kept) {
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
