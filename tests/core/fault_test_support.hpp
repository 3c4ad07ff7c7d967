// Small builders for the fault tests: frames from points, and a cubic lattice with planted
// planar faults (a slab of known dip and dip direction, optionally sheared), kept tiny on purpose.
#pragma once

#include "core/faults/fault.hpp"
#include "core/faults/plane_fit.hpp"
#include "core/model/frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace faultline::core::testing {

struct Sphere {
    std::int64_t id;
    double x, y, z;
    double r = 0.5;
};

inline Frame frameOf(const std::vector<Sphere>& spheres) {
    Frame f;
    for (const Sphere& s : spheres) {
        f.ids.push_back(s.id);
        f.x.push_back(float(s.x));
        f.y.push_back(float(s.y));
        f.z.push_back(float(s.z));
        f.radius.push_back(float(s.r));
    }
    f.finalize();
    return f;
}

inline Fault faultOf(std::string name, std::vector<std::int64_t> ids) {
    Fault f;
    f.name = std::move(name);
    f.add(std::move(ids));
    return f;
}

inline double dot3(const Vec3d& a, const Vec3d& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// A planar fault zone: spheres whose initial centre lies within halfWidth of the plane through
// `point` with orientation (dip, dipDirection), and inside [boxMin, boxMax].
struct PlantedFault {
    double dip = 45, dipDirection = 0;
    Vec3d point{0, 0, 0};
    double halfWidth = 2.0;
    Vec3d boxMin{-1e9, -1e9, -1e9}, boxMax{1e9, 1e9, 1e9};
    // Normal-sense slip of the hanging wall, down dip, ramped linearly across the zone.
    double slip = 0;

    double distance(const Vec3d& p) const {
        const Vec3d n = normalFromOrientation(dip, dipDirection);
        return dot3(n, {p[0] - point[0], p[1] - point[1], p[2] - point[2]});
    }
    bool inBox(const Vec3d& p) const {
        for (int a = 0; a < 3; ++a)
            if (p[a] < boxMin[a] || p[a] > boxMax[a])
                return false;
        return true;
    }
    bool contains(const Vec3d& p) const { return inBox(p) && std::fabs(distance(p)) < halfWidth; }
};

struct PlantedModel {
    Frame frame;
    std::vector<std::vector<std::int64_t>> members; // per planted fault, sorted
    std::vector<std::uint8_t> visible;              // members plus noise
};

// Cubic lattice (spacing 1, radius 0.5) of nx x ny x nz spheres; rows in a shuffled order and
// ids 1000 + lattice index, so nothing can lean on rows and ids agreeing. `noisePerMille`
// random spheres are visible too. With any slip, x0 y0 z0 columns hold the lattice positions.
inline PlantedModel plantFaults(int nx, int ny, int nz, const std::vector<PlantedFault>& faults,
                                unsigned noisePerMille = 3, unsigned seed = 7) {
    std::mt19937 rng(seed);
    const std::size_t n = std::size_t(nx) * ny * nz;
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i)
        order[i] = std::uint32_t(i);
    for (std::size_t i = n - 1; i > 0; --i)
        std::swap(order[i], order[rng() % (i + 1)]);
    bool anySlip = std::any_of(faults.begin(), faults.end(), [](auto& f) { return f.slip != 0; });

    PlantedModel m;
    m.members.resize(faults.size());
    std::vector<float> x0, y0, z0, strain;
    for (std::uint32_t li : order) {
        const int ix = int(li % nx), iy = int((li / nx) % ny), iz = int(li / nx / ny);
        const Vec3d p0{double(ix), double(iy), double(iz)};
        Vec3d p = p0;
        bool member = false;
        for (std::size_t k = 0; k < faults.size(); ++k) {
            const PlantedFault& f = faults[k];
            if (f.contains(p0)) {
                member = true;
                m.members[k].push_back(1000 + li);
            }
            if (f.slip != 0 && f.inBox(p0)) {
                const double s = f.distance(p0);
                const double ramp = std::clamp((s + f.halfWidth) / (2 * f.halfWidth), 0.0, 1.0);
                const Vec3d down = downDipVector(normalFromOrientation(f.dip, f.dipDirection));
                for (int a = 0; a < 3; ++a)
                    p[a] += f.slip * ramp * down[a];
            }
        }
        const bool noise = !member && rng() % 1000 < noisePerMille;
        m.frame.ids.push_back(1000 + li);
        m.frame.x.push_back(float(p[0]));
        m.frame.y.push_back(float(p[1]));
        m.frame.z.push_back(float(p[2]));
        m.frame.radius.push_back(0.5f);
        x0.push_back(float(p0[0]));
        y0.push_back(float(p0[1]));
        z0.push_back(float(p0[2]));
        strain.push_back(member || noise ? 1.0f : 0.0f);
        m.visible.push_back(member || noise ? 1 : 0);
    }
    m.frame.attributes.push_back(makeAttribute("strain", std::move(strain), false));
    if (anySlip) {
        m.frame.attributes.push_back(makeAttribute("x0", std::move(x0), false));
        m.frame.attributes.push_back(makeAttribute("y0", std::move(y0), false));
        m.frame.attributes.push_back(makeAttribute("z0", std::move(z0), false));
    }
    m.frame.finalize();
    for (auto& ids : m.members)
        std::sort(ids.begin(), ids.end());
    return m;
}

// |a - b| on the circle of 360 degrees (or of `period`).
inline double angleDiff(double a, double b, double period = 360.0) {
    double d = std::fmod(std::fabs(a - b), period);
    return std::min(d, period - d);
}

} // namespace faultline::core::testing
