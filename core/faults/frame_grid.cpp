#include "core/faults/frame_grid.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

namespace faultline::core::detail {

FrameGrid::FrameGrid(const Frame& frame, double spheresPerCell) {
    const std::size_t n = frame.size();
    auto finite = [&](std::size_t r) {
        return std::isfinite(frame.x[r]) && std::isfinite(frame.y[r]) && std::isfinite(frame.z[r]);
    };
    // finalize() gives the bounds of the finite centres, unless the first centre is not finite
    // (then they are NaN) or some is infinite; then scan.
    Vec3d lo{frame.centreMin()[0], frame.centreMin()[1], frame.centreMin()[2]};
    Vec3d hi{frame.centreMax()[0], frame.centreMax()[1], frame.centreMax()[2]};
    std::size_t count = n;
    if (!std::all_of(lo.begin(), lo.end(), [](double v) { return std::isfinite(v); }) ||
        !std::all_of(hi.begin(), hi.end(), [](double v) { return std::isfinite(v); })) {
        lo = {std::numeric_limits<double>::infinity(), 0, 0};
        lo[1] = lo[2] = lo[0];
        hi = {-lo[0], -lo[0], -lo[0]};
        count = 0;
        for (std::size_t r = 0; r < n; ++r) {
            if (!finite(r))
                continue;
            ++count;
            const Vec3d p{frame.x[r], frame.y[r], frame.z[r]};
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], p[a]);
                hi[a] = std::max(hi[a], p[a]);
            }
        }
    }
    if (count == 0) {
        m_start.assign(2, 0);
        return;
    }
    m_origin = lo;
    const double target = std::max(1.0, double(count) / std::max(1.0, spheresPerCell));
    const double largest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (largest > 0) {
        double volume = 1;
        for (int a = 0; a < 3; ++a)
            volume *= std::max(hi[a] - lo[a], largest * 1e-3);
        m_cell = std::cbrt(volume / target);
        for (;;) {
            double cells = 1;
            for (int a = 0; a < 3; ++a) {
                m_dims[a] = std::min<std::int64_t>(
                    1024, static_cast<std::int64_t>((hi[a] - lo[a]) / m_cell) + 1);
                cells *= double(m_dims[a]);
            }
            if (cells <= 4 * target + 64)
                break;
            m_cell *= 1.26;
        }
    }
    const std::size_t cells = std::size_t(m_dims[0] * m_dims[1] * m_dims[2]);
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> cellOf(n);
    const double inv = 1.0 / m_cell;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const auto& range) {
        // Finite centres lie within the bounds: truncation is the floor, and the clamp only
        // catches the rounding at the upper bound.
        auto coord = [&](int axis, float v) {
            const auto c = static_cast<std::int64_t>((double(v) - m_origin[axis]) * inv);
            return std::clamp<std::int64_t>(c, 0, m_dims[axis] - 1);
        };
        for (std::size_t r = range.begin(); r != range.end(); ++r)
            cellOf[r] = finite(r) ? std::uint32_t(coord(0, frame.x[r]) +
                                                  m_dims[0] * (coord(1, frame.y[r]) +
                                                               m_dims[1] * coord(2, frame.z[r])))
                                  : kNone;
    });
    m_start.assign(cells + 1, 0);
    count = 0;
    for (std::uint32_t c : cellOf)
        if (c != kNone) {
            ++m_start[c + 1];
            ++count;
        }
    for (std::size_t c = 0; c < cells; ++c)
        m_start[c + 1] += m_start[c];
    m_rows.resize(count);
    m_x.resize(count);
    m_y.resize(count);
    m_z.resize(count);
    std::vector<std::uint32_t> fill(m_start.begin(), m_start.end() - 1);
    for (std::size_t r = 0; r < n; ++r) {
        const std::uint32_t c = cellOf[r];
        if (c == kNone)
            continue;
        const std::uint32_t k = fill[c]++;
        m_rows[k] = std::uint32_t(r);
        m_x[k] = frame.x[r];
        m_y[k] = frame.y[r];
        m_z[k] = frame.z[r];
    }
}

} // namespace faultline::core::detail
