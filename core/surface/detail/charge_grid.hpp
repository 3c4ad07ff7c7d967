// Multilevel summation's anterpolation: every sphere's weight spread over a coarse level's nodes
// (a ChargeGrid), and the contiguous lists a coarse node's window sum adds up (WindowList).
#pragma once

#include "core/surface/detail/field_level.hpp"
#include "core/surface/detail/sphere_tree.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace faultline::core::detail {

// What a coarse node's window sum adds up: contiguous columns, padded with weightless entries to
// whole vectors of 8 (the sums take a vector at a time).
struct WindowList {
    std::vector<float> x, y, z, w;
    void clear() { x.clear(), y.clear(), z.clear(), w.clear(); }
    void push(float px, float py, float pz, float pw) {
        x.push_back(px), y.push_back(py), z.push_back(pz), w.push_back(pw);
    }
    void pad() {
        while (w.size() % 8 != 0)
            push(0.0f, 0.0f, 0.0f, 0.0f);
    }
};

// Every sphere's weight spread over a level's nodes with the interpolation's own Lagrange
// weights. Summing a smooth kernel over these charges sums, over the spheres, its interpolant at
// their centres: an error of the same size as interpolating the level's values, and far fewer
// terms where a node spacing holds many spheres. Dense over the centres' box, so for coarse
// levels only.
struct ChargeGrid {
    float spacing = 1.0f;
    Int3 lo{0, 0, 0}, dims{0, 0, 0};
    std::vector<float> q; // x slowest, z fastest
    std::size_t nonzero = 0;
    float at(int i, int j, int k) const {
        return q[(static_cast<std::size_t>(i) * dims[1] + j) * dims[2] + k];
    }
    // The nonzero charges within `cutoff` of the nodes [first, first + size) (all of them for
    // a cutoff of infinity), padded.
    void gather(const Int3& first, int size, float cutoff, WindowList& out) const;
};

// Largest grid anterpolate() makes (a level that fine for the spheres' box holds few spheres
// per node anyway).
inline constexpr std::size_t kMaxChargeNodes = std::size_t{1} << 22;

// The charges of a level of this spacing, or none when the grid over the centres' box would
// have more than kMaxChargeNodes nodes.
std::optional<ChargeGrid> anterpolate(const PackedSpheres& s, const Box& centres, float spacing);

} // namespace faultline::core::detail
