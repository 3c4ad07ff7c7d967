#include "core/faults/candidates.hpp"
#include "core/util/enum_names.hpp"

#include "core/faults/fault_network.hpp"
#include "core/faults/plane_fit.hpp"
#include "core/faults/sphere_cells.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace faultline::core {

namespace {

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

} // namespace

CandidateSet candidatesFromGroups(const Frame& frame, std::span<const std::int32_t> groupOfRow,
                                  std::size_t groupCount, std::size_t minSize) {
    assert(groupOfRow.size() == frame.size());
    CandidateSet result;
    result.rowLabel.assign(frame.size(), -1);
    std::vector<std::uint32_t> size(groupCount, 0);
    for (std::int32_t g : groupOfRow)
        if (g >= 0)
            ++size[static_cast<std::size_t>(g)];
    constexpr std::uint32_t kDropped = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> slot(groupCount, kDropped); // group -> candidate slot
    std::vector<Candidate> found;
    for (std::size_t g = 0; g < groupCount; ++g)
        if (size[g] > 0 && size[g] >= std::max<std::size_t>(minSize, 1)) {
            slot[g] = static_cast<std::uint32_t>(found.size());
            found.emplace_back().ids.reserve(size[g]);
        }
    for (std::size_t row = 0; row < groupOfRow.size(); ++row)
        if (const std::int32_t g = groupOfRow[row]; g >= 0 && slot[std::size_t(g)] != kDropped)
            found[slot[std::size_t(g)]].ids.push_back(frame.ids[row]);
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
    for (std::size_t row = 0; row < groupOfRow.size(); ++row)
        if (const std::int32_t g = groupOfRow[row]; g >= 0 && slot[std::size_t(g)] != kDropped)
            result.rowLabel[row] = static_cast<std::int32_t>(rank[slot[std::size_t(g)]]);
    return result;
}

namespace {

// Connected components: neighbours when |c_i - c_j| < link (r_i + r_j). Per row the
// component's root slot, hidden rows -1; unlinkable visible rows stand alone.
CandidateSet findConnected(const Frame& frame, std::span<const std::uint8_t> visible,
                           const CandidateOptions& options) {
    const std::vector<std::uint32_t> rows = detail::linkableRows(frame, visible);
    double rmax = 0;
    for (std::uint32_t r : rows)
        rmax = std::max(rmax, static_cast<double>(frame.radius[r]));
    const double reach = options.link * 2.0 * rmax;
    const detail::SphereCells cells(frame, rows, std::isfinite(reach) ? reach : 0.0);
    const std::size_t n = cells.size();
    const std::vector<float>&sx = cells.x, &sy = cells.y, &sz = cells.z, &sr = cells.r;

    ConcurrentUnionFind sets(n);
    if (reach > 0 && std::isfinite(reach)) {
        const double k = options.link;
        auto linked = [&](std::uint32_t i, std::uint32_t j) {
            const double dx = double(sx[i]) - sx[j], dy = double(sy[i]) - sy[j],
                         dz = double(sz[i]) - sz[j];
            const double limit = k * (double(sr[i]) + sr[j]);
            return dx * dx + dy * dy + dz * dz < limit * limit;
        };
        // Each pair of cells once: a cell with itself, and with every neighbour of higher index.
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, cells.cellCount(), 256), [&](const auto& range) {
                for (std::size_t c = range.begin(); c != range.end(); ++c) {
                    const std::uint32_t b = cells.cellBegin(c), e = cells.cellEnd(c);
                    cells.forEachNeighbourCell(c, [&](std::size_t other) {
                        if (other < c)
                            return;
                        for (std::uint32_t i = b; i < e; ++i)
                            for (std::uint32_t j = other == c ? i + 1 : cells.cellBegin(other);
                                 j < cells.cellEnd(other); ++j)
                                if (linked(i, j))
                                    sets.unite(i, j);
                    });
                }
            });
    }
    std::vector<std::int32_t> group(frame.size(), -1);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
            group[cells.row[i]] =
                static_cast<std::int32_t>(sets.find(static_cast<std::uint32_t>(i)));
    });
    std::size_t groups = n;
    for (std::size_t row = 0; row < frame.size(); ++row)
        if (visible[row] && group[row] < 0)
            group[row] = static_cast<std::int32_t>(groups++);
    return candidatesFromGroups(frame, group, groups, options.minSize);
}

} // namespace

CandidateSet findCandidates(const Frame& frame, std::span<const std::uint8_t> visible,
                            const CandidateOptions& options) {
    assert(visible.size() == frame.size());
    if (!(options.link > 0) || !std::isfinite(options.link))
        throw std::invalid_argument("candidate link factor must be a finite number > 0, not " +
                                    std::to_string(options.link));
    if (options.method == CandidateMethod::Connected)
        return findConnected(frame, visible, options);
    if (!(options.angle > 0 && options.angle < 90))
        throw std::invalid_argument("candidate angle must lie between 0 and 90 degrees, not " +
                                    std::to_string(options.angle));
    if (!(options.radius >= 0) || !std::isfinite(options.radius))
        throw std::invalid_argument(
            "candidate neighbourhood radius must be a finite number >= 0, not " +
            std::to_string(options.radius));
    const detail::NetworkGroups groups = detail::faultNetworkGroups(frame, visible, options);
    return candidatesFromGroups(frame, groups.groupOfRow, groups.groupCount, options.minSize);
}

namespace {
constexpr EnumName<CandidateMethod> kMethods[] = {{CandidateMethod::Network, "network"},
                                                  {CandidateMethod::Connected, "connected"}};
} // namespace

std::string_view candidateMethodName(CandidateMethod method) {
    return nameIn(kMethods, method, "network");
}

CandidateMethod parseCandidateMethod(std::string_view name) {
    if (const auto method = valueIn(kMethods, name))
        return *method;
    throw std::invalid_argument("method must be " + namesIn(kMethods, " or ") + ", not \"" +
                                std::string(name) + "\"");
}

std::array<float, 3> candidateColor(std::size_t index) {
    // Hue steps of the golden angle keep consecutive colours far apart; three value levels
    // separate colours whose hues come close again after many steps.
    const double hue = std::fmod(0.1 + 0.381966011250105 * static_cast<double>(index), 1.0) * 6.0;
    const double sat = 0.75,
                 val = (index / 7) % 3 == 1 ? 0.75 : ((index / 7) % 3 == 2 ? 0.6 : 0.95);
    const int sector = static_cast<int>(hue) % 6;
    const double f = hue - std::floor(hue);
    const double p = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
    double rgb[3];
    switch (sector) {
    case 0:
        rgb[0] = val, rgb[1] = t, rgb[2] = p;
        break;
    case 1:
        rgb[0] = q, rgb[1] = val, rgb[2] = p;
        break;
    case 2:
        rgb[0] = p, rgb[1] = val, rgb[2] = t;
        break;
    case 3:
        rgb[0] = p, rgb[1] = q, rgb[2] = val;
        break;
    case 4:
        rgb[0] = t, rgb[1] = p, rgb[2] = val;
        break;
    default:
        rgb[0] = val, rgb[1] = p, rgb[2] = q;
        break;
    }
    return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

CandidateShape candidateShape(const Frame& frame, std::span<const std::int64_t> ids) {
    CandidateShape out;
    std::vector<Vec3d> points;
    points.reserve(ids.size());
    for (std::int64_t id : ids)
        if (auto row = frame.rowOf(id))
            points.push_back({frame.x[*row], frame.y[*row], frame.z[*row]});
    const auto& lo = frame.centreMin();
    const auto& hi = frame.centreMax();
    const int thin = sectionAxisOfSpheres({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]},
                                          2.0 * frame.meanRadius());
    const PlaneFit fit = fitPlane(points, thin);
    if (!fit.valid)
        return out;
    out.valid = true;
    out.dip = fit.orientation.dip;
    out.dipDirection = fit.orientation.dipDirection;
    // Across: the spread along the normal. Within: the smaller spread in the plane; in a
    // section (the plane holds the thin axis) the spread along the fault, the largest one.
    double across = 0;
    for (const Vec3d& p : points) {
        const double d = (p[0] - fit.centroid[0]) * fit.normal[0] +
                         (p[1] - fit.centroid[1]) * fit.normal[1] +
                         (p[2] - fit.centroid[2]) * fit.normal[2];
        across += d * d;
    }
    across /= double(points.size());
    const double within = thin >= 0 ? fit.eigenvalues[2] : fit.eigenvalues[1];
    out.thicknessRatio = within > 0 ? std::sqrt(across / within) : 1.0;
    out.diffuse =
        out.thicknessRatio > (thin >= 0 ? kDiffuseSectionThicknessRatio : kDiffuseThicknessRatio);
    out.subHorizontal = out.dip < kSubHorizontalDip;
    return out;
}

std::string diffuseNote(const CandidateShape& shape) {
    if (!shape.valid || !shape.diffuse)
        return {};
    char text[128];
    std::snprintf(text, sizeof text,
                  "diffuse: its spheres fill a volume (thickness %.2f of its width), not one "
                  "fault plane",
                  shape.thicknessRatio);
    return text;
}

std::string shapeNote(const CandidateShape& shape) {
    std::string note = diffuseNote(shape);
    if (shape.valid && shape.subHorizontal) {
        char dip[32];
        std::snprintf(dip, sizeof dip, "%.1f", shape.dip);
        note += (note.empty() ? "" : "; ") + std::string("sub-horizontal: dips ") + dip +
                " degrees; often a layer along the model's surface or base (a creeping free "
                "surface, a basal detachment) rather than a dipping fault; in a shear box, the "
                "shear zone";
    }
    return note;
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
