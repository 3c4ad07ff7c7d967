#include "core/synth/fault_bands.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace faultline::core {

namespace {

struct Point {
    double x, z, w;
};

// The heaviest band over all dips and offsets (sliding window over the sorted projections).
DippingBand heaviestBand(const std::vector<Point>& pts, const FaultBandOptions& o) {
    DippingBand best;
    double bestSpread = 0;
    std::vector<std::pair<double, double>> proj(pts.size());
    for (double dip = o.minDip; dip <= o.maxDip + 1e-9; dip += o.dipStep) {
        const double rad = dip * std::numbers::pi / 180.0;
        const double sn = std::sin(rad), cs = std::cos(rad);
        for (int s = 1; s >= -1; s -= 2) {
            for (std::size_t i = 0; i < pts.size(); ++i)
                proj[i] = {pts[i].x * sn + s * pts[i].z * cs, pts[i].w};
            std::sort(proj.begin(), proj.end());
            double sum = 0;
            std::size_t lo = 0;
            for (std::size_t hi = 0; hi < proj.size(); ++hi) {
                sum += proj[hi].second;
                while (proj[hi].first - proj[lo].first > o.width)
                    sum -= proj[lo++].second;
                // Ties go to the tightest window: the dip that fits the damage best.
                const double spread = proj[hi].first - proj[lo].first;
                if (sum > best.weight + 1e-9 ||
                    (sum > best.weight - 1e-9 && spread < bestSpread - 1e-9)) {
                    bestSpread = spread;
                    best.weight = sum;
                    best.dip = dip;
                    best.towardsPlusX = s;
                    best.offset = 0.5 * (proj[lo].first + proj[hi].first);
                }
            }
        }
    }
    return best;
}

double greedyShare(std::vector<Point> pts, const FaultBandOptions& o,
                   std::vector<DippingBand>* out) {
    double total = 0;
    for (const auto& p : pts)
        total += p.w;
    if (total <= 0)
        return 0;
    double inside = 0;
    for (int k = 0; k < o.bands; ++k) {
        const DippingBand b = heaviestBand(pts, o);
        if (b.weight <= 0)
            break;
        inside += b.weight;
        if (out)
            out->push_back(b);
        const double rad = b.dip * std::numbers::pi / 180.0;
        const double sn = std::sin(rad), cs = std::cos(rad);
        std::erase_if(pts, [&](const Point& p) {
            return std::fabs(p.x * sn + b.towardsPlusX * p.z * cs - b.offset) <=
                   0.5 * o.width + 1e-9;
        });
    }
    return inside / total;
}

} // namespace

FaultBandMeasure measureFaultBands(const Frame& frame, const FaultBandOptions& options) {
    const AttributeColumn* broken = frame.attribute("broken_bonds");
    assert(broken && "measureFaultBands needs a broken_bonds column");
    const AttributeColumn* type = options.skipBoundaryTypes ? frame.attribute("type") : nullptr;
    std::vector<Point> damaged, all;
    for (std::size_t i = 0; i < frame.size(); ++i) {
        if (type && type->value(i) != 1)
            continue;
        const double w = broken->value(i);
        all.push_back({frame.x[i], frame.z[i], 1.0});
        if (w > 0)
            damaged.push_back({frame.x[i], frame.z[i], w});
    }
    FaultBandMeasure m;
    m.damagedShare = greedyShare(std::move(damaged), options, &m.bands);
    m.uniformShare = greedyShare(std::move(all), options, nullptr);
    return m;
}

} // namespace faultline::core
