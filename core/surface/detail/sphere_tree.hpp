// SphereTree: a kd-tree over sphere centres with per-node weight and radius range. It answers
// "which spheres lie within R of this box" and gives field bounds over boxes (surface planning).
#pragma once

#include "core/surface/sphere_set.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace faultline::core::detail {

struct Box {
    std::array<float, 3> lo{0, 0, 0};
    std::array<float, 3> hi{0, 0, 0};
};

// Squared smallest and largest distances between points of two boxes (inline: surface planning
// calls them millions of times).
inline float minDistance2(const Box& a, const Box& b) {
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k) {
        const float below = a.lo[k] - b.hi[k], above = b.lo[k] - a.hi[k];
        const float gap = below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
        d2 += gap * gap;
    }
    return d2;
}

inline float maxDistance2(const Box& a, const Box& b) {
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k) {
        const float span = std::max(a.hi[k] - b.lo[k], b.hi[k] - a.lo[k]);
        d2 += span * span;
    }
    return d2;
}

// Spheres in tree order (structure of arrays), weights w = radius.
struct PackedSpheres {
    std::vector<float> x, y, z, r, red, green, blue;
    std::size_t size() const { return x.size(); }
};

struct TreeNode {
    Box box;
    float weight = 0; // sum of radii
    float rmin = 0, rmax = 0;
    std::uint32_t begin = 0, end = 0; // range in tree order
    std::int32_t left = -1, right = -1;
    bool leaf() const { return left < 0; }
};

// Spheres near a box, gathered into contiguous arrays for vectorisable loops.
struct NearList {
    std::vector<float> x, y, z, r, red, green, blue;
    void clear();
    std::size_t size() const { return x.size(); }
};

// Appends sphere i of p to out when its centre lies within sqrt(reach2) of box (the gathers'
// one test, so that the tree and the grid keep exactly the same spheres).
inline void appendIfWithin(const PackedSpheres& p, std::uint32_t i, const Box& box, float reach2,
                           NearList& out, bool withColor) {
    float d2 = 0.0f;
    const float c[3] = {p.x[i], p.y[i], p.z[i]};
    for (int k = 0; k < 3; ++k) {
        const float gap = std::max(0.0f, std::max(box.lo[k] - c[k], c[k] - box.hi[k]));
        d2 += gap * gap;
    }
    if (d2 > reach2)
        return;
    out.x.push_back(c[0]);
    out.y.push_back(c[1]);
    out.z.push_back(c[2]);
    out.r.push_back(p.r[i]);
    if (withColor) {
        out.red.push_back(p.red[i]);
        out.green.push_back(p.green[i]);
        out.blue.push_back(p.blue[i]);
    }
}

class SphereTree {
  public:
    explicit SphereTree(const SphereSet& spheres);

    const PackedSpheres& spheres() const { return m_spheres; }
    const std::vector<TreeNode>& nodes() const { return m_nodes; }
    const TreeNode& root() const { return m_nodes.front(); }

    // Appends every sphere whose centre lies within `reach` of `box`.
    void gather(const Box& box, float reach, NearList& out, bool withColor) const;
    // Ranges [first, second) of tree order that hold every sphere within `reach` of `box` (and
    // some a little farther, from leaves only partly in reach): no copies.
    void gatherRanges(const Box& box, float reach,
                      std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const;

  private:
    std::int32_t build(std::vector<std::uint32_t>& order, std::uint32_t begin, std::uint32_t end);
    PackedSpheres m_spheres;
    std::vector<TreeNode> m_nodes;
    std::vector<std::array<float, 3>> m_centres; // scratch during build
    std::vector<float> m_radii;
};

} // namespace faultline::core::detail
