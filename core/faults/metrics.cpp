#include "core/faults/metrics.hpp"
#include "core/util/enum_names.hpp"

#include "core/faults/frame_grid.hpp"
#include "core/faults/tracking.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <memory>

namespace faultline::core {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr Vec3d kNaN3{kNaN, kNaN, kNaN};

double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

struct DisplacementColumns {
    const AttributeColumn* x0 = nullptr;
    const AttributeColumn* y0 = nullptr;
    const AttributeColumn* z0 = nullptr;
    bool present() const { return x0 && y0 && z0; }
};

// The cells (one mean diameter square) that member centres project into on the fault plane,
// in strike (u) and down-dip (v) coordinates from the centroid: the area, and the patch whose
// neighbouring spheres measure the throw. Lookups use a bitmap over the cells' bounding
// rectangle when it is not much larger than the footprint, else a binary search.
class Footprint {
  public:
    Footprint(std::vector<std::uint64_t> keys, double cell)
        : m_cell(cell), m_keys(std::move(keys)) {
        std::sort(m_keys.begin(), m_keys.end());
        m_keys.erase(std::unique(m_keys.begin(), m_keys.end()), m_keys.end());
        if (m_keys.empty())
            return;
        m_uMin = m_vMin = std::numeric_limits<std::int32_t>::max();
        m_uMax = m_vMax = std::numeric_limits<std::int32_t>::min();
        for (std::uint64_t k : m_keys) {
            m_uMin = std::min(m_uMin, keyU(k));
            m_uMax = std::max(m_uMax, keyU(k));
            m_vMin = std::min(m_vMin, keyV(k));
            m_vMax = std::max(m_vMax, keyV(k));
        }
        m_width = std::int64_t(m_uMax) - m_uMin + 1;
        const std::int64_t height = std::int64_t(m_vMax) - m_vMin + 1;
        if (m_width * height <= 64 * std::int64_t(m_keys.size()) + 65536) {
            m_bitmap.assign(std::size_t(m_width * height), 0);
            for (std::uint64_t k : m_keys)
                m_bitmap[std::size_t((keyV(k) - std::int64_t(m_vMin)) * m_width +
                                     (keyU(k) - std::int64_t(m_uMin)))] = 1;
        }
    }

    static std::int32_t index(double w, double cell) {
        return static_cast<std::int32_t>(
            std::clamp(std::floor(w / cell), -2147483648.0, 2147483647.0));
    }
    static std::uint64_t key(std::int32_t iu, std::int32_t iv) {
        return (std::uint64_t(std::uint32_t(iu)) << 32) | std::uint32_t(iv);
    }
    static std::int32_t keyU(std::uint64_t k) { return std::int32_t(std::uint32_t(k >> 32)); }
    static std::int32_t keyV(std::uint64_t k) { return std::int32_t(std::uint32_t(k)); }

    std::size_t cellCount() const { return m_keys.size(); }
    double area() const { return double(m_keys.size()) * m_cell * m_cell; }
    // Extents of the occupied cells along u (strike) and v (down dip).
    double lengthU() const {
        return m_keys.empty() ? 0.0 : double(std::int64_t(m_uMax) - m_uMin + 1) * m_cell;
    }
    double lengthV() const {
        return m_keys.empty() ? 0.0 : double(std::int64_t(m_vMax) - m_vMin + 1) * m_cell;
    }

    bool contains(double u, double v) const {
        if (m_keys.empty())
            return false;
        const std::int32_t iu = index(u, m_cell), iv = index(v, m_cell);
        if (iu < m_uMin || iu > m_uMax || iv < m_vMin || iv > m_vMax)
            return false;
        if (!m_bitmap.empty())
            return m_bitmap[std::size_t((std::int64_t(iv) - m_vMin) * m_width +
                                        (std::int64_t(iu) - m_uMin))] != 0;
        return std::binary_search(m_keys.begin(), m_keys.end(), key(iu, iv));
    }
    // Whether a ball of this radius around (u, v) can meet the footprint's bounding rectangle.
    bool nearBounds(double u, double v, double radius) const {
        return !m_keys.empty() && u >= m_uMin * m_cell - radius &&
               u <= (double(m_uMax) + 1) * m_cell + radius && v >= m_vMin * m_cell - radius &&
               v <= (double(m_vMax) + 1) * m_cell + radius;
    }

  private:
    double m_cell;
    std::vector<std::uint64_t> m_keys; // sorted, unique
    std::int32_t m_uMin = 0, m_uMax = -1, m_vMin = 0, m_vMax = -1;
    std::int64_t m_width = 0;
    std::vector<std::uint8_t> m_bitmap;
};

FaultFrameMetrics computeOne(const Frame& frame, std::size_t frameIndex, std::size_t faultIndex,
                             const Fault& fault, const MetricsOptions& options,
                             const DisplacementColumns& displacement,
                             const detail::FrameGrid* grid) {
    FaultFrameMetrics m;
    m.frame = frameIndex;
    m.fault = faultIndex;
    m.name = fault.name;
    const std::vector<std::uint32_t> rows = memberRows(frame, fault.ids);
    m.count = rows.size();

    std::vector<Vec3d> points(rows.size());
    double radiusSum = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const std::uint32_t r = rows[i];
        points[i] = {frame.x[r], frame.y[r], frame.z[r]};
        radiusSum += frame.radius[r];
    }
    m.min = m.max = kNaN3;
    if (!points.empty()) {
        m.min = m.max = points[0];
        for (const auto& p : points)
            for (int a = 0; a < 3; ++a) {
                m.min[a] = std::min(m.min[a], p[a]);
                m.max[a] = std::max(m.max[a], p[a]);
            }
    }
    m.meanRadius = rows.empty() ? kNaN : radiusSum / double(rows.size());

    m.broken = 0;
    m.brokenCentroid = kNaN3;
    if (const AttributeColumn* bonds = frame.attribute(options.brokenBondsVariable)) {
        Vec3d sum{0, 0, 0};
        for (std::size_t i = 0; i < rows.size(); ++i)
            if (bonds->value(rows[i]) > 0) {
                ++m.broken;
                for (int a = 0; a < 3; ++a)
                    sum[a] += points[i][a];
            }
        if (m.broken > 0)
            for (int a = 0; a < 3; ++a)
                m.brokenCentroid[a] = sum[a] / double(m.broken);
    }

    // A section model (a slab of several sphere layers, thin along one axis): fault planes
    // contain that axis, else the fit would find the slab's own plane.
    const Vec3d extent{double(frame.centreMax()[0]) - frame.centreMin()[0],
                       double(frame.centreMax()[1]) - frame.centreMin()[1],
                       double(frame.centreMax()[2]) - frame.centreMin()[2]};
    // A single layer (extent within a radius) is left alone: there the layer may be the fault.
    int section = sectionAxisOfSpheres(extent, 2.0 * frame.meanRadius());
    if (section >= 0 && !(extent[section] > m.meanRadius))
        section = -1;
    const PlaneFit fit = fitPlane(points, section);
    m.centroid = fit.centroid;
    m.planeValid = fit.valid;
    m.normal = fit.normal;
    m.eigenvalues = fit.eigenvalues;
    m.dip = fit.orientation.dip;
    m.dipDirection = fit.orientation.dipDirection;
    m.strike = fit.orientation.strike;
    m.thickness = m.area = m.length = m.height = kNaN;
    m.slip = kNaN3;
    m.throwVertical = m.netSlip = m.dipSlip = m.strikeSlip = kNaN;
    m.throwStatus = !options.computeThrow     ? ThrowStatus::Disabled
                    : !displacement.present() ? ThrowStatus::NoDisplacement
                                              : ThrowStatus::NoPlane;
    if (!fit.valid)
        return m;

    const Vec3d& n = fit.normal;
    const Vec3d& c = fit.centroid;
    double sumSq = 0;
    for (const auto& p : points) {
        const double s = dot(n, sub(p, c));
        sumSq += s * s;
    }
    m.thickness = std::sqrt(12.0 * sumSq / double(points.size()));

    const double diameter = 2.0 * m.meanRadius;
    if (!(diameter > 0) || !std::isfinite(diameter))
        return m; // no cell size for the area, no slab width for the throw
    const Vec3d along = strikeVector(n), down = downDipVector(n);
    std::vector<std::uint64_t> keys(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3d d = sub(points[i], c);
        keys[i] = Footprint::key(Footprint::index(dot(along, d), diameter),
                                 Footprint::index(dot(down, d), diameter));
    }
    const Footprint footprint(std::move(keys), diameter);
    m.area = footprint.area();
    m.length = footprint.lengthU();
    m.height = footprint.lengthV();

    if (m.throwStatus != ThrowStatus::NoPlane || grid == nullptr)
        return m;
    const double inner = m.thickness / 2 + options.throwGapDiameters * diameter;
    const double outer = inner + options.throwSlabDiameters * diameter;
    Vec3d lo = m.min, hi = m.max;
    for (int a = 0; a < 3; ++a) {
        lo[a] -= outer;
        hi[a] += outer;
    }
    Vec3d sum[2] = {{0, 0, 0}, {0, 0, 0}}; // footwall, hanging wall
    std::size_t samples[2] = {0, 0};
    const double halfDiagonal = grid->cellSize() * std::sqrt(3.0) / 2;
    auto acceptCell = [&](const Vec3d& centre) {
        const Vec3d d = sub(centre, c);
        return footprint.nearBounds(dot(along, d), dot(down, d), halfDiagonal);
    };
    const float* xs = grid->xs().data();
    const float* ys = grid->ys().data();
    const float* zs = grid->zs().data();
    const std::uint32_t* gridRows = grid->rows().data();
    const Vec3d centre = c, normal = n;
    grid->forEachNearPlane(lo, hi, c, n, outer, acceptCell, [&](std::uint32_t k) {
        const Vec3d d{xs[k] - centre[0], ys[k] - centre[1], zs[k] - centre[2]};
        const double s = dot(normal, d);
        if (std::fabs(s) < inner || std::fabs(s) > outer)
            return;
        if (!footprint.contains(dot(along, d), dot(down, d)))
            return;
        const std::uint32_t r = gridRows[k];
        if (fault.contains(frame.ids[r]))
            return;
        const Vec3d u{double(xs[k]) - displacement.x0->value(r),
                      double(ys[k]) - displacement.y0->value(r),
                      double(zs[k]) - displacement.z0->value(r)};
        if (!std::isfinite(u[0]) || !std::isfinite(u[1]) || !std::isfinite(u[2]))
            return;
        const int side = s > 0 ? 1 : 0;
        ++samples[side];
        for (int a = 0; a < 3; ++a)
            sum[side][a] += u[a];
    });
    m.footwallSamples = samples[0];
    m.hangingWallSamples = samples[1];
    const std::size_t need = std::max<std::size_t>(1, options.throwMinSamples);
    if (samples[0] < need || samples[1] < need) {
        m.throwStatus = ThrowStatus::TooFewSamples;
        return m;
    }
    m.throwStatus = ThrowStatus::Ok;
    for (int a = 0; a < 3; ++a)
        m.slip[a] = sum[1][a] / double(samples[1]) - sum[0][a] / double(samples[0]);
    m.throwVertical = m.slip[2];
    m.netSlip = std::sqrt(dot(m.slip, m.slip));
    m.dipSlip = dot(m.slip, down);
    m.strikeSlip = dot(m.slip, along);
    return m;
}

} // namespace

namespace {
constexpr EnumName<ThrowStatus> kThrowStatuses[] = {
    {ThrowStatus::Ok, "ok"},
    {ThrowStatus::Disabled, "disabled"},
    {ThrowStatus::NoDisplacement, "no_displacement"},
    {ThrowStatus::NoPlane, "no_plane"},
    {ThrowStatus::TooFewSamples, "too_few_samples"}};
} // namespace

std::string_view throwStatusName(ThrowStatus status) {
    return nameIn(kThrowStatuses, status, "unknown");
}

std::vector<FaultFrameMetrics> computeFrameMetrics(const Frame& frame, std::size_t frameIndex,
                                                   std::span<const Fault> faults,
                                                   const MetricsOptions& options) {
    DisplacementColumns displacement{frame.attribute("x0"), frame.attribute("y0"),
                                     frame.attribute("z0")};
    // No initial positions in the file: the reference positions of strain from motion
    // (ref_x, ref_y, ref_z; unprefixed first, so a cumulative set since frame 0 is preferred).
    if (!displacement.present()) {
        auto refs = [&](const std::string& prefix) {
            return DisplacementColumns{frame.attribute(prefix + "ref_x"),
                                       frame.attribute(prefix + "ref_y"),
                                       frame.attribute(prefix + "ref_z")};
        };
        displacement = refs("");
        for (const AttributeColumn& c : frame.attributes) {
            if (displacement.present())
                break;
            if (c.name.size() > 5 && c.name.ends_with("ref_x"))
                displacement = refs(c.name.substr(0, c.name.size() - 5));
        }
    }
    std::unique_ptr<detail::FrameGrid> grid;
    if (options.computeThrow && displacement.present() && !faults.empty())
        grid = std::make_unique<detail::FrameGrid>(frame);
    std::vector<FaultFrameMetrics> result(faults.size());
    tbb::parallel_for(std::size_t(0), faults.size(), [&](std::size_t k) {
        result[k] = computeOne(frame, frameIndex, k, faults[k], options, displacement, grid.get());
    });
    return result;
}

std::vector<FaultSeed> seedsFromRows(std::span<const FaultFrameMetrics> rows,
                                     std::size_t faultCount) {
    std::vector<FaultSeed> seeds(faultCount);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const FaultFrameMetrics& m = rows[i];
        assert(m.fault == i % faultCount);
        FaultSeed& s = seeds[m.fault];
        if (s.found || m.broken == 0)
            continue;
        s = {true, m.frame, m.broken, m.brokenCentroid};
    }
    return seeds;
}

FaultMetricsSeries computeMetricsSeries(std::size_t frameCount, const FrameLoader& load,
                                        std::span<const Fault> faults,
                                        const MetricsOptions& options,
                                        const FrameSelection& selection) {
    FaultMetricsSeries series;
    series.frameCount = frameCount;
    series.faultCount = faults.size();
    series.selection = selection;
    series.rows.resize(frameCount * faults.size());
    for (std::size_t i = 0; i < series.rows.size(); ++i) {
        series.rows[i].frame = i / faults.size();
        series.rows[i].fault = i % faults.size();
    }
    const std::vector<std::size_t> frames = selection.frames(frameCount);
    tbb::parallel_for(std::size_t(0), frames.size(), [&](std::size_t i) {
        const std::size_t f = frames[i];
        const std::shared_ptr<const Frame> frame = load(f);
        std::vector<FaultFrameMetrics> rows = computeFrameMetrics(*frame, f, faults, options);
        std::move(rows.begin(), rows.end(),
                  series.rows.begin() + std::ptrdiff_t(f * faults.size()));
    });
    if (faults.empty())
        return series;
    series.seeds = seedsFromRows(series.rows, faults.size());
    if (!selection.everything()) {
        // A seed is the first break in any frame: read the frames outside the selection, in
        // order, until every fault has one (their rows only feed the seeds).
        MetricsOptions seedOnly = options;
        seedOnly.computeThrow = false;
        for (std::size_t f = 0; f < frameCount; ++f) {
            const bool missing =
                std::any_of(series.seeds.begin(), series.seeds.end(),
                            [&](const FaultSeed& s) { return !s.found || s.frame > f; });
            if (!missing)
                break;
            if (selection.contains(f))
                continue;
            std::vector<FaultFrameMetrics> rows =
                computeFrameMetrics(*load(f), f, faults, seedOnly);
            std::move(rows.begin(), rows.end(),
                      series.rows.begin() + std::ptrdiff_t(f * faults.size()));
            series.seeds = seedsFromRows(series.rows, faults.size());
        }
    }
    return series;
}

} // namespace faultline::core
