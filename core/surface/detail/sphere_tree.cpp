#include "core/surface/detail/sphere_tree.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace faultline::core::detail {

namespace {
constexpr std::uint32_t kLeafSize = 8;
}

void NearList::clear() {
    for (auto* v : {&x, &y, &z, &r, &red, &green, &blue})
        v->clear();
}

SphereTree::SphereTree(const SphereSet& s) {
    const std::size_t n = s.size();
    assert(n > 0 && s.consistent());
    m_centres.resize(n);
    m_radii.assign(s.radius.begin(), s.radius.end());
    for (std::size_t i = 0; i < n; ++i)
        m_centres[i] = {s.x[i], s.y[i], s.z[i]};
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i)
        order[i] = static_cast<std::uint32_t>(i);
    m_nodes.reserve(2 * n / kLeafSize + 2);
    build(order, 0, static_cast<std::uint32_t>(n));

    auto& p = m_spheres;
    for (auto* v : {&p.x, &p.y, &p.z, &p.r, &p.red, &p.green, &p.blue})
        v->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t src = order[i];
        p.x[i] = s.x[src];
        p.y[i] = s.y[src];
        p.z[i] = s.z[src];
        p.r[i] = s.radius[src];
        const bool white = s.rgb.empty();
        p.red[i] = white ? 1.0f : s.rgb[3 * src];
        p.green[i] = white ? 1.0f : s.rgb[3 * src + 1];
        p.blue[i] = white ? 1.0f : s.rgb[3 * src + 2];
    }
    m_centres.clear();
    m_centres.shrink_to_fit();
    m_radii.clear();
    m_radii.shrink_to_fit();
}

std::int32_t SphereTree::build(std::vector<std::uint32_t>& order, std::uint32_t begin,
                               std::uint32_t end) {
    const auto index = static_cast<std::int32_t>(m_nodes.size());
    m_nodes.emplace_back();
    TreeNode node;
    node.begin = begin;
    node.end = end;
    constexpr float inf = std::numeric_limits<float>::infinity();
    node.box.lo = {inf, inf, inf};
    node.box.hi = {-inf, -inf, -inf};
    node.rmin = inf;
    double weight = 0.0;
    for (std::uint32_t i = begin; i < end; ++i) {
        const auto& c = m_centres[order[i]];
        for (int k = 0; k < 3; ++k) {
            node.box.lo[k] = std::min(node.box.lo[k], c[k]);
            node.box.hi[k] = std::max(node.box.hi[k], c[k]);
        }
        const float r = m_radii[order[i]];
        weight += r;
        node.rmin = std::min(node.rmin, r);
        node.rmax = std::max(node.rmax, r);
    }
    node.weight = static_cast<float>(weight);
    if (end - begin > kLeafSize) {
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (node.box.hi[k] - node.box.lo[k] > node.box.hi[axis] - node.box.lo[axis])
                axis = k;
        const std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             return m_centres[a][axis] < m_centres[b][axis];
                         });
        node.left = build(order, begin, mid);
        node.right = build(order, mid, end);
    }
    m_nodes[index] = node;
    return index;
}

void SphereTree::gather(const Box& box, float reach, NearList& out, bool withColor) const {
    const float reach2 = reach * reach;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    const auto& p = m_spheres;
    while (top > 0) {
        const TreeNode& node = m_nodes[stack[--top]];
        if (minDistance2(node.box, box) > reach2)
            continue;
        // Largest distance from a point of the node's box to the query box (per axis bound).
        float far2 = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const float below = box.lo[k] - node.box.lo[k], above = node.box.hi[k] - box.hi[k];
            const float gap = std::max(0.0f, std::max(below, above));
            far2 += gap * gap;
        }
        if (far2 <= reach2) {
            // Every sphere of the node is in reach: copy its contiguous range.
            const auto b = static_cast<std::ptrdiff_t>(node.begin);
            const auto e = static_cast<std::ptrdiff_t>(node.end);
            out.x.insert(out.x.end(), p.x.begin() + b, p.x.begin() + e);
            out.y.insert(out.y.end(), p.y.begin() + b, p.y.begin() + e);
            out.z.insert(out.z.end(), p.z.begin() + b, p.z.begin() + e);
            out.r.insert(out.r.end(), p.r.begin() + b, p.r.begin() + e);
            if (withColor) {
                out.red.insert(out.red.end(), p.red.begin() + b, p.red.begin() + e);
                out.green.insert(out.green.end(), p.green.begin() + b, p.green.begin() + e);
                out.blue.insert(out.blue.end(), p.blue.begin() + b, p.blue.begin() + e);
            }
            continue;
        }
        if (!node.leaf()) {
            stack[top++] = node.left;
            stack[top++] = node.right;
            continue;
        }
        for (std::uint32_t i = node.begin; i < node.end; ++i)
            appendIfWithin(p, i, box, reach2, out, withColor);
    }
}

void SphereTree::gatherRanges(const Box& box, float reach,
                              std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) const {
    const float reach2 = reach * reach;
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const TreeNode& node = m_nodes[stack[--top]];
        if (minDistance2(node.box, box) > reach2)
            continue;
        float far2 = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const float below = box.lo[k] - node.box.lo[k], above = node.box.hi[k] - box.hi[k];
            const float gap = std::max(0.0f, std::max(below, above));
            far2 += gap * gap;
        }
        if (far2 <= reach2 || node.leaf()) {
            if (!out.empty() && out.back().second == node.begin)
                out.back().second = node.end;
            else
                out.emplace_back(node.begin, node.end);
            continue;
        }
        // Right first so that the left child (lower tree order) is taken next: ranges merge.
        stack[top++] = node.right;
        stack[top++] = node.left;
    }
}

} // namespace faultline::core::detail
