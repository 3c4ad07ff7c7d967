// UnionFind: sequential disjoint sets over 0..n-1 with path halving; the smaller index is always
// the root, so the result does not depend on the order of unions (deterministic groupings).
// (candidates.cpp has its own lock-free version for parallel unions.)
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace faultline::core {

struct UnionFind {
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b)
            parent[std::max(a, b)] = std::min(a, b);
    }
};

} // namespace faultline::core
