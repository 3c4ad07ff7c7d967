// Small synthetic scenes shared by the renderer tests: lattices of spheres with variables.
#pragma once

#include "core/model/frame.hpp"

#include <cmath>

namespace faultline::test {

// nx * ny * nz spheres of radius r on a unit grid from the origin, with variables "height" (z),
// "layer" (int, z index) and "strain" (a smooth field peaking on a dipping plane).
inline core::Frame makeLattice(int nx, int ny, int nz, float r = 0.5f) {
    core::Frame f;
    std::vector<float> height, strain;
    std::vector<float> layer;
    std::int64_t id = 1;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                f.ids.push_back(id++);
                f.x.push_back(float(i));
                f.y.push_back(float(j));
                f.z.push_back(float(k));
                f.radius.push_back(r);
                height.push_back(float(k));
                layer.push_back(float(k));
                // Distance to the plane x + 0.6 z = 0.5 nx, as a Gaussian band.
                const float d = (float(i) + 0.6f * float(k) - 0.5f * float(nx)) / 1.166f;
                strain.push_back(0.5f * std::exp(-d * d / 4.0f));
            }
    f.attributes.push_back(core::makeAttribute("height", std::move(height), false));
    f.attributes.push_back(core::makeAttribute("layer", std::move(layer), true));
    f.attributes.push_back(core::makeAttribute("strain", std::move(strain), false));
    f.finalize();
    return f;
}

} // namespace faultline::test
