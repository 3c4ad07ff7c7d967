#include "core/faults/sphere_cells.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace faultline::core::detail {

namespace {
constexpr std::uint64_t kNoCell = std::numeric_limits<std::uint64_t>::max();

std::size_t hashKey(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return static_cast<std::size_t>(k);
}
} // namespace

std::vector<std::uint32_t> linkableRows(const Frame& frame, std::span<const std::uint8_t> visible) {
    std::vector<std::uint32_t> rows;
    for (std::size_t r = 0; r < frame.size() && r < visible.size(); ++r)
        if (visible[r] && std::isfinite(frame.x[r]) && std::isfinite(frame.y[r]) &&
            std::isfinite(frame.z[r]) && std::isfinite(frame.radius[r]) && frame.radius[r] >= 0)
            rows.push_back(static_cast<std::uint32_t>(r));
    return rows;
}

SphereCells::SphereCells(const Frame& frame, std::span<const std::uint32_t> rows, double cell) {
    const std::size_t n = rows.size();
    double lo[3] = {std::numeric_limits<double>::infinity(), 0, 0};
    lo[1] = lo[2] = lo[0];
    double hi[3] = {-lo[0], -lo[0], -lo[0]};
    for (std::uint32_t r : rows) {
        const double p[3] = {frame.x[r], frame.y[r], frame.z[r]};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
    }
    if (n == 0) {
        m_cellBegin.push_back(0);
        return;
    }
    // A hair more than asked, so rounding in cell coordinates cannot put two points closer
    // than `cell` two cells apart; grown so no axis has more than 2^20 cells.
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    m_cell = std::max(
        {cell * (1.0 + 1e-9), extent / double(1 << 20), std::numeric_limits<double>::min()});
    for (int a = 0; a < 3; ++a)
        m_dims[a] = static_cast<std::uint64_t>(std::floor((hi[a] - lo[a]) / m_cell)) + 1;

    struct Keyed {
        std::uint64_t key;
        std::int64_t id;
        std::uint32_t row;
        bool operator<(const Keyed& o) const { return std::tie(key, id) < std::tie(o.key, o.id); }
    };
    std::vector<Keyed> keyed(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const std::uint32_t r = rows[i];
            const double p[3] = {frame.x[r], frame.y[r], frame.z[r]};
            std::uint64_t c[3];
            for (int a = 0; a < 3; ++a)
                c[a] = std::min(m_dims[a] - 1, static_cast<std::uint64_t>((p[a] - lo[a]) / m_cell));
            keyed[i] = {c[0] + m_dims[0] * (c[1] + m_dims[1] * c[2]), frame.ids[r], r};
        }
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());

    row.resize(n);
    x.resize(n);
    y.resize(n);
    z.resize(n);
    r.resize(n);
    m_cellOfSlot.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t fr = keyed[i].row;
        row[i] = fr;
        x[i] = frame.x[fr];
        y[i] = frame.y[fr];
        z[i] = frame.z[fr];
        r[i] = frame.radius[fr];
        if (i == 0 || keyed[i].key != keyed[i - 1].key) {
            m_cellKey.push_back(keyed[i].key);
            m_cellBegin.push_back(static_cast<std::uint32_t>(i));
        }
        m_cellOfSlot[i] = static_cast<std::uint32_t>(m_cellKey.size() - 1);
    }
    m_cellBegin.push_back(static_cast<std::uint32_t>(n));

    const double gridCells = double(m_dims[0]) * double(m_dims[1]) * double(m_dims[2]);
    if (gridCells <= std::max(4.0 * double(n), double(1 << 20))) {
        m_dense.assign(static_cast<std::size_t>(gridCells), -1);
        for (std::size_t c = 0; c < m_cellKey.size(); ++c)
            m_dense[m_cellKey[c]] = static_cast<std::int32_t>(c);
        return;
    }
    std::size_t cap = 16;
    while (cap < 2 * m_cellKey.size())
        cap *= 2;
    m_mask = cap - 1;
    m_slotKey.assign(cap, kNoCell);
    m_slotCell.assign(cap, 0);
    for (std::size_t c = 0; c < m_cellKey.size(); ++c) {
        std::size_t slot = hashKey(m_cellKey[c]) & m_mask;
        while (m_slotKey[slot] != kNoCell)
            slot = (slot + 1) & m_mask;
        m_slotKey[slot] = m_cellKey[c];
        m_slotCell[slot] = static_cast<std::uint32_t>(c);
    }
}

std::int64_t SphereCells::find(std::uint64_t key) const {
    if (!m_dense.empty())
        return m_dense[key];
    std::size_t slot = hashKey(key) & m_mask;
    for (;;) {
        const std::uint64_t k = m_slotKey[slot];
        if (k == key)
            return m_slotCell[slot];
        if (k == kNoCell)
            return -1;
        slot = (slot + 1) & m_mask;
    }
}

} // namespace faultline::core::detail
