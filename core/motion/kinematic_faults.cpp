#include "core/motion/kinematic_faults.hpp"

#include "core/faults/sphere_cells.hpp"
#include "core/model/periodic_cell.hpp"
#include "core/util/union_find.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

namespace faultline::core {

namespace {

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3d& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double median(std::vector<double> v) {
    if (v.empty())
        return 0;
    const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

// Solves the 6x6 system m x = b by Gaussian elimination with partial pivoting; false when
// singular.
bool solve6(std::array<std::array<double, 7>, 6> m, std::array<double, 6>& x) {
    for (int c = 0; c < 6; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 6; ++r)
            if (std::fabs(m[r][c]) > std::fabs(m[pivot][c]))
                pivot = r;
        if (!(std::fabs(m[pivot][c]) > 1e-300))
            return false;
        std::swap(m[c], m[pivot]);
        for (int r = c + 1; r < 6; ++r) {
            const double f = m[r][c] / m[c][c];
            for (int k = c; k < 7; ++k)
                m[r][k] -= f * m[c][k];
        }
    }
    for (int r = 5; r >= 0; --r) {
        double s = m[r][6];
        for (int k = r + 1; k < 6; ++k)
            s -= m[r][k] * x[k];
        x[r] = s / m[r][r];
    }
    return true;
}

// Least-squares u = t + w x (p - c) over the members (the linearised rigid motion).
RigidMotion fitRigid(const std::vector<Vec3d>& p, const std::vector<Vec3d>& u,
                     const std::vector<std::uint32_t>& members) {
    RigidMotion m;
    if (members.empty())
        return m;
    for (std::uint32_t i : members)
        for (int a = 0; a < 3; ++a)
            m.centre[a] += p[i][a] / double(members.size());
    // Rows of A per sphere: [I3 | -[q]x], unknowns (t, w); normal equations A^T A x = A^T u.
    std::array<std::array<double, 7>, 6> n{};
    for (std::uint32_t i : members) {
        const Vec3d q = sub(p[i], m.centre);
        const double rows[3][6] = {
            {1, 0, 0, 0, q[2], -q[1]}, {0, 1, 0, -q[2], 0, q[0]}, {0, 0, 1, q[1], -q[0], 0}};
        for (int r = 0; r < 3; ++r)
            for (int a = 0; a < 6; ++a) {
                for (int b = 0; b < 6; ++b)
                    n[a][b] += rows[r][a] * rows[r][b];
                n[a][6] += rows[r][a] * u[i][r];
            }
    }
    double trace = 0;
    for (int a = 0; a < 6; ++a)
        trace += n[a][a];
    for (int a = 0; a < 6; ++a)
        n[a][a] += 1e-9 * trace; // a line of spheres leaves a rotation undetermined
    std::array<double, 6> x{};
    if (!solve6(n, x))
        return m;
    m.translation = {x[0], x[1], x[2]};
    m.rotation = {x[3], x[4], x[5]};
    return m;
}

// The 10-90 % width of the change of motion across a fault: spheres within 6 d of the plane and
// 12 d of its centroid along it, each one's displacement as a fraction of the way from block b's
// median motion to block a's; the median fraction per half diameter of signed distance; the
// distance between where it crosses 0.1 and 0.9. Infinite when it never does.
double transitionWidth(const std::vector<Vec3d>& pos, const std::vector<Vec3d>& u,
                       const std::vector<std::int32_t>& label, std::int32_t a, std::int32_t b,
                       const PlaneFit& plane, double d, const PeriodicCell& cell) {
    Vec3d ua{}, ub{}; // each block's median motion
    for (int k = 0; k < 3; ++k) {
        std::vector<double> ca, cb;
        for (std::size_t i = 0; i < pos.size(); ++i) {
            if (label[i] == a)
                ca.push_back(u[i][k]);
            else if (label[i] == b)
                cb.push_back(u[i][k]);
        }
        ua[k] = median(std::move(ca));
        ub[k] = median(std::move(cb));
    }
    const Vec3d slip = sub(ua, ub);
    const double slip2 = slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2];
    if (!(slip2 > 0))
        return INFINITY;
    constexpr int kBins = 24; // -6 d .. 6 d in half diameters
    std::vector<std::vector<double>> bins(kBins);
    for (std::size_t i = 0; i < pos.size(); ++i) {
        double dx = pos[i][0] - plane.centroid[0], dy = pos[i][1] - plane.centroid[1],
               dz = pos[i][2] - plane.centroid[2];
        cell.wrap(dx, dy, dz);
        const double s = dx * plane.normal[0] + dy * plane.normal[1] + dz * plane.normal[2];
        const Vec3d along{dx - s * plane.normal[0], dy - s * plane.normal[1],
                          dz - s * plane.normal[2]};
        if (std::fabs(s) >= 6 * d || norm(along) >= 12 * d)
            continue;
        const Vec3d rel = sub(u[i], ub);
        const double fraction = (rel[0] * slip[0] + rel[1] * slip[1] + rel[2] * slip[2]) / slip2;
        bins[std::size_t(std::clamp(int(std::floor((s / d + 6) * 2)), 0, kBins - 1))].push_back(
            fraction);
    }
    std::vector<double> med(kBins, NAN);
    for (int k = 0; k < kBins; ++k)
        if (bins[std::size_t(k)].size() > 3)
            med[std::size_t(k)] = median(bins[std::size_t(k)]);
    // Rising with distance (block a on the positive side), else read backwards.
    double low = 0, high = 0;
    int nl = 0, nh = 0;
    for (int k = 0; k < kBins; ++k)
        if (!std::isnan(med[std::size_t(k)]))
            (k < kBins / 2 ? (low += med[std::size_t(k)], ++nl)
                           : (high += med[std::size_t(k)], ++nh));
    const bool rising = nl && nh ? high / nh >= low / nl : true;
    auto crossing = [&](double t) {
        for (int k = 0; k + 1 < kBins; ++k) {
            const int i = rising ? k : kBins - 1 - k, j = rising ? k + 1 : kBins - 2 - k;
            const double m0 = med[std::size_t(i)], m1 = med[std::size_t(j)];
            if (!std::isnan(m0) && !std::isnan(m1) && m0 < t && m1 >= t) {
                const double z0 = (i + 0.5) / 2 - 6, z1 = (j + 0.5) / 2 - 6;
                return z0 + (t - m0) / (m1 - m0) * (z1 - z0);
            }
        }
        return double(NAN);
    };
    const double w = std::fabs(crossing(0.9) - crossing(0.1));
    return std::isnan(w) ? INFINITY : w * d;
}

} // namespace

Vec3d RigidMotion::at(const Vec3d& p) const {
    const Vec3d r = cross(rotation, sub(p, centre));
    return {translation[0] + r[0], translation[1] + r[1], translation[2] + r[2]};
}

KinematicResult kinematicFaults(const Frame& before, const Frame& after,
                                const KinematicOptions& options) {
    KinematicResult out;
    out.blockOfRow.assign(after.size(), -1);
    // Matched spheres: positions (later frame), displacements (minimum image).
    const PeriodicCell cell(after.box);
    std::vector<std::uint32_t> rows; // rows of `after`
    std::vector<Vec3d> pos, u;
    double radiusSum = 0;
    for (std::uint32_t r = 0; r < after.size(); ++r) {
        const auto b = before.rowOf(after.ids[r]);
        if (!b || !std::isfinite(after.x[r]) || !std::isfinite(before.x[*b]) ||
            !(after.radius[r] > 0))
            continue;
        double dx = double(after.x[r]) - before.x[*b], dy = double(after.y[r]) - before.y[*b],
               dz = double(after.z[r]) - before.z[*b];
        cell.wrap(dx, dy, dz);
        if (!std::isfinite(dx + dy + dz))
            continue;
        rows.push_back(r);
        pos.push_back({after.x[r], after.y[r], after.z[r]});
        u.push_back({dx, dy, dz});
        radiusSum += after.radius[r];
    }
    const std::size_t n = rows.size();
    if (n < 2 * options.minBlock)
        throw std::invalid_argument("kinematic faults: the frames share only " + std::to_string(n) +
                                    " spheres");
    const double d = 2.0 * radiusSum / double(n);
    out.meanDiameter = d;

    // Neighbour pairs in the later frame (i < j).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    {
        const detail::SphereCells cells(after, rows, options.cutoff * d);
        std::vector<std::uint32_t> index(after.size(), 0);
        for (std::uint32_t k = 0; k < n; ++k)
            index[rows[k]] = k;
        const float limit = float(options.cutoff * d);
        for (std::size_t c = 0; c < cells.cellCount(); ++c)
            for (std::uint32_t i = cells.cellBegin(c); i < cells.cellEnd(c); ++i)
                cells.forEachNeighbourCell(c, [&](std::size_t other) {
                    for (std::uint32_t j = cells.cellBegin(other); j < cells.cellEnd(other); ++j) {
                        const std::uint32_t a = index[cells.row[i]], b = index[cells.row[j]];
                        if (a >= b)
                            continue;
                        const float dx = cells.x[j] - cells.x[i], dy = cells.y[j] - cells.y[i],
                                    dz = cells.z[j] - cells.z[i];
                        if (dx * dx + dy * dy + dz * dz < limit * limit)
                            pairs.push_back({a, b});
                    }
                });
        std::sort(pairs.begin(), pairs.end()); // independent of the frame's row order
    }

    // 1. Seeds.
    Vec3d mu{};
    for (int a = 0; a < 3; ++a) {
        std::vector<double> c(n);
        for (std::size_t i = 0; i < n; ++i)
            c[i] = u[i][a];
        mu[a] = median(std::move(c));
    }
    std::vector<double> spread(n);
    for (std::size_t i = 0; i < n; ++i)
        spread[i] = norm(sub(u[i], mu));
    std::nth_element(spread.begin(), spread.begin() + std::ptrdiff_t(0.9 * double(n - 1)),
                     spread.end());
    const double s90 = spread[std::size_t(0.9 * double(n - 1))];
    const double tol = std::max(options.beta * s90, options.floor * d);
    const std::size_t minBlock =
        std::max(options.minBlock, std::size_t(options.minBlockFraction * double(n)));
    std::vector<std::int32_t> label(n, -1);
    std::vector<RigidMotion> motions;
    {
        UnionFind sets(n);
        for (const auto& [i, j] : pairs)
            if (norm(sub(u[i], u[j])) < tol)
                sets.unite(i, j);
        std::map<std::uint32_t, std::vector<std::uint32_t>> pieces;
        for (std::uint32_t i = 0; i < n; ++i)
            pieces[sets.find(i)].push_back(i);
        std::vector<std::vector<std::uint32_t>> seeds;
        for (auto& [root, members] : pieces)
            if (members.size() >= minBlock)
                seeds.push_back(std::move(members));
        if (seeds.size() < 2)
            return out; // one rigid body (or none): no fault
        for (const auto& s : seeds)
            motions.push_back(fitRigid(pos, u, s));
    }

    std::vector<double> misfit(n, 0.0);
    auto assign = [&] {
        for (std::size_t i = 0; i < n; ++i) {
            double best = INFINITY;
            for (std::size_t k = 0; k < motions.size(); ++k) {
                const double e = norm(sub(u[i], motions[k].at(pos[i])));
                if (e < best)
                    best = e, label[i] = std::int32_t(k);
            }
            misfit[i] = best;
        }
        // Pieces of one block smaller than a block take their neighbours' majority.
        for (int round = 0; round < 5; ++round) {
            UnionFind same(n);
            for (const auto& [i, j] : pairs)
                if (label[i] == label[j])
                    same.unite(i, j);
            std::vector<std::size_t> size(n, 0);
            for (std::uint32_t i = 0; i < n; ++i)
                ++size[same.find(i)];
            std::map<std::uint32_t, std::map<std::int32_t, std::size_t>> votes;
            for (const auto& [i, j] : pairs) {
                const std::uint32_t a = same.find(i), b = same.find(j);
                if (a == b)
                    continue;
                if (size[a] < minBlock)
                    ++votes[a][label[j]];
                if (size[b] < minBlock)
                    ++votes[b][label[i]];
            }
            std::map<std::uint32_t, std::int32_t> relabel;
            for (const auto& [piece, v] : votes) {
                const auto best =
                    std::max_element(v.begin(), v.end(), [](const auto& x, const auto& y) {
                        return x.second < y.second;
                    });
                relabel[piece] = best->first;
            }
            bool changed = false;
            for (std::uint32_t i = 0; i < n; ++i)
                if (auto it = relabel.find(same.find(i));
                    it != relabel.end() && it->second != label[i])
                    label[i] = it->second, changed = true;
            if (!changed)
                break;
        }
    };

    for (int round = 0; round < options.rounds; ++round) {
        assign();
        const std::size_t k = motions.size();
        std::vector<std::size_t> size(k, 0), interior(k, 0);
        std::vector<std::uint8_t> border(n, 0);
        for (const auto& [i, j] : pairs)
            if (label[i] != label[j])
                border[i] = border[j] = 1;
        for (std::size_t i = 0; i < n; ++i) {
            ++size[std::size_t(label[i])];
            interior[std::size_t(label[i])] += border[i] ? 0 : 1;
        }
        std::size_t big = 0;
        for (std::size_t b = 0; b < k; ++b)
            big += size[b] >= minBlock;
        long dissolve = -1;
        double least = options.minInterior;
        if (big > 2)
            for (std::size_t b = 0; b < k; ++b) {
                const double share =
                    double(interior[b]) / double(std::max<std::size_t>(size[b], 1));
                if (size[b] >= minBlock && share < least)
                    least = share, dissolve = long(b);
            }
        std::vector<RigidMotion> next;
        for (std::size_t b = 0; b < k; ++b) {
            if (size[b] < minBlock || long(b) == dissolve)
                continue;
            std::vector<std::uint32_t> members;
            for (std::uint32_t i = 0; i < n; ++i)
                if (label[i] == std::int32_t(b))
                    members.push_back(i);
            RigidMotion m = fitRigid(pos, u, members);
            for (int trim = 0; trim < 2; ++trim) {
                std::vector<double> e;
                for (std::uint32_t i : members)
                    e.push_back(norm(sub(u[i], m.at(pos[i]))));
                const double limit = std::max(3.0 * median(e), options.floor * d);
                std::vector<std::uint32_t> good;
                for (std::size_t t = 0; t < members.size(); ++t)
                    if (e[t] <= limit)
                        good.push_back(members[t]);
                m = fitRigid(pos, u, good);
            }
            next.push_back(m);
        }
        motions = std::move(next);
        if (motions.size() < 2)
            return out;
    }
    assign();

    // Blocks largest first.
    const std::size_t k = motions.size();
    std::vector<std::size_t> size(k, 0);
    for (std::int32_t l : label)
        ++size[std::size_t(l)];
    std::vector<std::size_t> order(k);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return size[a] > size[b]; });
    std::vector<std::int32_t> rank(k);
    for (std::size_t r = 0; r < k; ++r)
        rank[order[r]] = std::int32_t(r);
    for (std::size_t r = 0; r < k; ++r) {
        out.blocks.push_back(motions[order[r]]);
        out.blockSizes.push_back(size[order[r]]);
        std::vector<double> e;
        for (std::size_t i = 0; i < n; ++i)
            if (label[i] == std::int32_t(order[r]))
                e.push_back(misfit[i]);
        out.blockMisfit.push_back(median(std::move(e)));
    }
    for (std::size_t i = 0; i < n; ++i) {
        label[i] = rank[std::size_t(label[i])];
        out.blockOfRow[rows[i]] = label[i];
    }

    // 4. Faults between blocks.
    const int thin = sectionAxisOfSpheres({double(after.centreMax()[0]) - after.centreMin()[0],
                                           double(after.centreMax()[1]) - after.centreMin()[1],
                                           double(after.centreMax()[2]) - after.centreMin()[2]},
                                          d);
    out.sectionAxis = thin;
    for (std::size_t a = 0; a < k; ++a)
        for (std::size_t b = a + 1; b < k; ++b) {
            const double quiet =
                std::max(std::min(out.blockMisfit[a], out.blockMisfit[b]), options.floor * d);
            const double rough =
                std::max({out.blockMisfit[a], out.blockMisfit[b], options.floor * d});
            std::vector<Vec3d> mids;
            for (const auto& [i, j] : pairs) {
                const bool ab = (label[i] == std::int32_t(a) && label[j] == std::int32_t(b)) ||
                                (label[i] == std::int32_t(b) && label[j] == std::int32_t(a));
                if (!ab)
                    continue;
                double dx = pos[j][0] - pos[i][0], dy = pos[j][1] - pos[i][1],
                       dz = pos[j][2] - pos[i][2];
                cell.wrap(dx, dy, dz);
                const Vec3d mid{pos[i][0] + 0.5 * dx, pos[i][1] + 0.5 * dy, pos[i][2] + 0.5 * dz};
                if (norm(sub(out.blocks[a].at(mid), out.blocks[b].at(mid))) >
                    std::max(4.0 * quiet, 0.05 * d))
                    mids.push_back(mid);
            }
            if (mids.size() < 3)
                continue;
            // Periodic axes: midpoints brought next to the first one.
            for (Vec3d& m : mids) {
                double dx = m[0] - mids[0][0], dy = m[1] - mids[0][1], dz = m[2] - mids[0][2];
                cell.wrap(dx, dy, dz);
                m = {mids[0][0] + dx, mids[0][1] + dy, mids[0][2] + dz};
            }
            auto rmsOf = [&](const PlaneFit& f, const std::vector<Vec3d>& pts) {
                double s = 0;
                for (const Vec3d& p : pts) {
                    const Vec3d q = sub(p, f.centroid);
                    const double t = q[0] * f.normal[0] + q[1] * f.normal[1] + q[2] * f.normal[2];
                    s += t * t;
                }
                return std::sqrt(s / double(pts.size()));
            };
            PlaneFit fit = fitPlane(mids, thin);
            if (!fit.valid)
                continue;
            const double rms0 = rmsOf(fit, mids);
            std::vector<Vec3d> kept;
            for (const Vec3d& p : mids) {
                const Vec3d q = sub(p, fit.centroid);
                if (std::fabs(q[0] * fit.normal[0] + q[1] * fit.normal[1] + q[2] * fit.normal[2]) <=
                    options.trim * rms0)
                    kept.push_back(p);
            }
            if (kept.size() >= 3)
                if (PlaneFit refit = fitPlane(kept, thin); refit.valid)
                    fit = refit, mids = std::move(kept);
            KinematicFault f;
            f.blockA = a;
            f.blockB = b;
            f.midpoints = mids.size();
            f.plane = fit;
            f.rms = rmsOf(fit, mids);
            f.points = std::move(mids);
            f.slip = norm(sub(out.blocks[a].at(fit.centroid), out.blocks[b].at(fit.centroid)));
            f.width =
                transitionWidth(pos, u, label, std::int32_t(a), std::int32_t(b), fit, d, cell);
            f.identifiable = f.midpoints >= 30 && f.rms < 1.5 * d && f.slip > 3.0 * rough &&
                             f.width <= options.maxWidth * d;
            out.faults.push_back(f);
        }
    std::stable_sort(
        out.faults.begin(), out.faults.end(),
        [](const KinematicFault& x, const KinematicFault& y) { return x.midpoints > y.midpoints; });
    return out;
}

} // namespace faultline::core
