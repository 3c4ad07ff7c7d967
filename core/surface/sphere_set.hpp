// SphereSet: the spheres a fault surface is built from, as views of the caller's columns.
// Nothing is copied into library types: a Frame's columns or a gathered fault subset both fit.
#pragma once

#include <cstddef>
#include <span>

namespace faultline::core {

struct SphereSet {
    std::span<const float> x, y, z; // centres, world units
    std::span<const float> radius;  // one per sphere (> 0)
    std::span<const float> rgb;     // 3 floats (r, g, b in [0, 1]) per sphere, or empty: all white

    std::size_t size() const { return x.size(); }
    // True when every column has the length size() asks for.
    bool consistent() const {
        return y.size() == x.size() && z.size() == x.size() && radius.size() == x.size() &&
               (rgb.empty() || rgb.size() == 3 * x.size());
    }
};

} // namespace faultline::core
