#include "core/faults/candidates.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace faultline::core {

namespace {

constexpr std::uint64_t kNoCell = std::numeric_limits<std::uint64_t>::max();

// Union-find safe under concurrent unite(): a root is only ever linked below a smaller index
// by compare-and-swap, and path halving only shortens paths, so parent[i] <= i always holds
// and no cycle can form. After the writers join, find() gives one root per component.
class ConcurrentUnionFind {
  public:
    explicit ConcurrentUnionFind(std::size_t n) : m_parent(n) {
        for (std::size_t i = 0; i < n; ++i)
            m_parent[i].store(static_cast<std::uint32_t>(i), std::memory_order_relaxed);
    }
    std::uint32_t find(std::uint32_t x) {
        for (;;) {
            std::uint32_t p = m_parent[x].load(std::memory_order_relaxed);
            if (p == x)
                return x;
            const std::uint32_t gp = m_parent[p].load(std::memory_order_relaxed);
            if (gp != p)
                m_parent[x].compare_exchange_weak(p, gp, std::memory_order_relaxed);
            x = gp;
        }
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        for (;;) {
            a = find(a);
            b = find(b);
            if (a == b)
                return;
            if (a < b)
                std::swap(a, b);
            std::uint32_t expected = a;
            if (m_parent[a].compare_exchange_strong(expected, b, std::memory_order_relaxed))
                return;
        }
    }

  private:
    std::vector<std::atomic<std::uint32_t>> m_parent;
};

// Open addressing: occupied cell key -> index of the cell in the sorted cell list.
class CellIndex {
  public:
    explicit CellIndex(std::span<const std::uint64_t> keys) {
        std::size_t cap = 16;
        while (cap < 2 * keys.size())
            cap *= 2;
        m_mask = cap - 1;
        m_keys.assign(cap, kNoCell);
        m_cells.assign(cap, 0);
        for (std::size_t c = 0; c < keys.size(); ++c) {
            std::size_t slot = hash(keys[c]) & m_mask;
            while (m_keys[slot] != kNoCell)
                slot = (slot + 1) & m_mask;
            m_keys[slot] = keys[c];
            m_cells[slot] = static_cast<std::uint32_t>(c);
        }
    }
    // Cell index, or -1 when the cell holds no sphere.
    std::int64_t find(std::uint64_t key) const {
        std::size_t slot = hash(key) & m_mask;
        for (;;) {
            const std::uint64_t k = m_keys[slot];
            if (k == key)
                return m_cells[slot];
            if (k == kNoCell)
                return -1;
            slot = (slot + 1) & m_mask;
        }
    }

  private:
    static std::size_t hash(std::uint64_t k) {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return static_cast<std::size_t>(k);
    }
    std::size_t m_mask = 0;
    std::vector<std::uint64_t> m_keys;
    std::vector<std::uint32_t> m_cells;
};

} // namespace

CandidateSet findCandidates(const Frame& frame, std::span<const std::uint8_t> visible,
                            const CandidateOptions& options) {
    assert(visible.size() == frame.size());
    if (!(options.link > 0) || !std::isfinite(options.link))
        throw std::invalid_argument("candidate link factor must be a finite number > 0, not " +
                                    std::to_string(options.link));
    CandidateSet result;
    result.rowLabel.assign(frame.size(), -1);

    std::vector<std::uint32_t> rows;
    for (std::size_t r = 0; r < frame.size(); ++r)
        if (visible[r])
            rows.push_back(static_cast<std::uint32_t>(r));
    const std::size_t n = rows.size();
    if (n == 0)
        return result;

    // Bounds and the largest neighbour distance among spheres that can have neighbours.
    auto linkable = [&](std::uint32_t r) {
        return std::isfinite(frame.x[r]) && std::isfinite(frame.y[r]) &&
               std::isfinite(frame.z[r]) && std::isfinite(frame.radius[r]) &&
               frame.radius[r] >= 0;
    };
    double lo[3] = {std::numeric_limits<double>::infinity(), 0, 0};
    lo[1] = lo[2] = lo[0];
    double hi[3] = {-lo[0], -lo[0], -lo[0]};
    double rmax = 0;
    for (std::uint32_t r : rows) {
        if (!linkable(r))
            continue;
        const double p[3] = {frame.x[r], frame.y[r], frame.z[r]};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
        rmax = std::max(rmax, static_cast<double>(frame.radius[r]));
    }
    const double reach = options.link * 2.0 * rmax;
    const bool anyLinks = reach > 0 && std::isfinite(reach) && lo[0] <= hi[0];

    // Cell size: the reach (a hair more, so rounding in the cell coordinates cannot put two
    // neighbours two cells apart), grown if needed so no axis has more than 2^20 cells.
    double cell = reach * (1.0 + 1e-9);
    std::uint64_t dims[3] = {1, 1, 1};
    if (anyLinks) {
        const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
        cell = std::max(cell, extent / double(1 << 20));
        for (int a = 0; a < 3; ++a)
            dims[a] = static_cast<std::uint64_t>(std::floor((hi[a] - lo[a]) / cell)) + 1;
    }

    // Sort spheres by cell; unlinkable spheres go last under kNoCell.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const std::uint32_t r = rows[i];
            std::uint64_t key = kNoCell;
            if (anyLinks && linkable(r)) {
                const double p[3] = {frame.x[r], frame.y[r], frame.z[r]};
                std::uint64_t c[3];
                for (int a = 0; a < 3; ++a)
                    c[a] = std::min(dims[a] - 1,
                                    static_cast<std::uint64_t>((p[a] - lo[a]) / cell));
                key = c[0] + dims[0] * (c[1] + dims[1] * c[2]);
            }
            keyed[i] = {key, r};
        }
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());

    std::vector<float> sx(n), sy(n), sz(n), sr(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t r = keyed[i].second;
        sx[i] = frame.x[r];
        sy[i] = frame.y[r];
        sz[i] = frame.z[r];
        sr[i] = frame.radius[r];
    }
    std::vector<std::uint64_t> cellKeys;
    std::vector<std::uint32_t> cellBegin;
    for (std::size_t i = 0; i < n; ++i) {
        if (keyed[i].first == kNoCell)
            break;
        if (i == 0 || keyed[i].first != keyed[i - 1].first) {
            cellKeys.push_back(keyed[i].first);
            cellBegin.push_back(static_cast<std::uint32_t>(i));
        }
    }
    const std::size_t cellCount = cellKeys.size();
    cellBegin.push_back(static_cast<std::uint32_t>(
        cellCount == 0 ? 0
                       : std::partition_point(keyed.begin(), keyed.end(),
                                              [](const auto& k) { return k.first != kNoCell; }) -
                             keyed.begin()));

    ConcurrentUnionFind sets(n);
    if (cellCount > 0) {
        const CellIndex index(cellKeys);
        const double k = options.link;
        auto linked = [&](std::uint32_t i, std::uint32_t j) {
            const double dx = double(sx[i]) - sx[j], dy = double(sy[i]) - sy[j],
                         dz = double(sz[i]) - sz[j];
            const double limit = k * (double(sr[i]) + sr[j]);
            return dx * dx + dy * dy + dz * dz < limit * limit;
        };
        // Half of the 26 neighbour offsets: each pair of cells is visited once.
        int offsets[13][3];
        int count = 0;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (dz > 0 || (dz == 0 && (dy > 0 || (dy == 0 && dx > 0)))) {
                        offsets[count][0] = dx;
                        offsets[count][1] = dy;
                        offsets[count][2] = dz;
                        ++count;
                    }
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cellCount, 256), [&](const auto& range) {
            for (std::size_t c = range.begin(); c != range.end(); ++c) {
                const std::uint32_t b = cellBegin[c], e = cellBegin[c + 1];
                for (std::uint32_t i = b; i < e; ++i)
                    for (std::uint32_t j = i + 1; j < e; ++j)
                        if (linked(i, j))
                            sets.unite(i, j);
                const std::uint64_t key = cellKeys[c];
                const std::int64_t cx = static_cast<std::int64_t>(key % dims[0]);
                const std::int64_t cy = static_cast<std::int64_t>((key / dims[0]) % dims[1]);
                const std::int64_t cz = static_cast<std::int64_t>(key / dims[0] / dims[1]);
                for (const auto& o : offsets) {
                    const std::int64_t nx = cx + o[0], ny = cy + o[1], nz = cz + o[2];
                    if (nx < 0 || ny < 0 || nz < 0 || nx >= std::int64_t(dims[0]) ||
                        ny >= std::int64_t(dims[1]) || nz >= std::int64_t(dims[2]))
                        continue;
                    const std::int64_t other = index.find(
                        std::uint64_t(nx) + dims[0] * (std::uint64_t(ny) + dims[1] * std::uint64_t(nz)));
                    if (other < 0)
                        continue;
                    const std::uint32_t ob = cellBegin[other], oe = cellBegin[other + 1];
                    for (std::uint32_t i = b; i < e; ++i)
                        for (std::uint32_t j = ob; j < oe; ++j)
                            if (linked(i, j))
                                sets.unite(i, j);
                }
            }
        });
    }

    // Group by root: sizes, then the members of components that pass minSize.
    std::vector<std::uint32_t> root(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
            root[i] = sets.find(static_cast<std::uint32_t>(i));
    });
    std::vector<std::uint32_t> size(n, 0);
    for (std::uint32_t r : root)
        ++size[r];
    constexpr std::uint32_t kDropped = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> slot(n, kDropped); // root -> candidate slot
    std::vector<std::uint32_t> roots;
    for (std::size_t i = 0; i < n; ++i)
        if (root[i] == i && size[i] >= std::max<std::size_t>(options.minSize, 1)) {
            slot[i] = static_cast<std::uint32_t>(roots.size());
            roots.push_back(static_cast<std::uint32_t>(i));
        }
    std::vector<Candidate> found(roots.size());
    for (std::size_t c = 0; c < roots.size(); ++c)
        found[c].ids.reserve(size[roots[c]]);
    for (std::size_t i = 0; i < n; ++i)
        if (const std::uint32_t s = slot[root[i]]; s != kDropped)
            found[s].ids.push_back(frame.ids[keyed[i].second]);
    tbb::parallel_for(std::size_t(0), found.size(),
                      [&](std::size_t c) { std::sort(found[c].ids.begin(), found[c].ids.end()); });
    std::vector<std::uint32_t> order(found.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (found[a].size() != found[b].size())
            return found[a].size() > found[b].size();
        return found[a].ids.front() < found[b].ids.front();
    });
    std::vector<std::uint32_t> rank(found.size());
    result.candidates.reserve(found.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        rank[order[k]] = static_cast<std::uint32_t>(k);
        result.candidates.push_back(std::move(found[order[k]]));
    }
    for (std::size_t i = 0; i < n; ++i)
        if (const std::uint32_t s = slot[root[i]]; s != kDropped)
            result.rowLabel[keyed[i].second] = static_cast<std::int32_t>(rank[s]);
    return result;
}

std::array<float, 3> candidateColor(std::size_t index) {
    // Hue steps of the golden angle keep consecutive colours far apart; three value levels
    // separate colours whose hues come close again after many steps.
    const double hue = std::fmod(0.1 + 0.381966011250105 * static_cast<double>(index), 1.0) * 6.0;
    const double sat = 0.75, val = (index / 7) % 3 == 1 ? 0.75 : ((index / 7) % 3 == 2 ? 0.6 : 0.95);
    const int sector = static_cast<int>(hue) % 6;
    const double f = hue - std::floor(hue);
    const double p = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
    double rgb[3];
    switch (sector) {
    case 0: rgb[0] = val, rgb[1] = t, rgb[2] = p; break;
    case 1: rgb[0] = q, rgb[1] = val, rgb[2] = p; break;
    case 2: rgb[0] = p, rgb[1] = val, rgb[2] = t; break;
    case 3: rgb[0] = p, rgb[1] = q, rgb[2] = val; break;
    case 4: rgb[0] = t, rgb[1] = p, rgb[2] = val; break;
    default: rgb[0] = val, rgb[1] = p, rgb[2] = q; break;
    }
    return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

std::vector<Fault> faultsFromCandidates(std::span<const Candidate> candidates,
                                        std::string_view prefix) {
    std::vector<Fault> faults;
    faults.reserve(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        Fault f;
        f.name = std::string(prefix) + std::to_string(i + 1);
        f.color = candidateColor(i);
        f.ids = candidates[i].ids;
        faults.push_back(std::move(f));
    }
    return faults;
}

} // namespace faultline::core
