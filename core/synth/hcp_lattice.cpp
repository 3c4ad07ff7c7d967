#include "core/synth/hcp_lattice.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace faultline::core {

HcpLattice makeHcpLattice(int columns, int layers, int rows, double radius) {
    assert(columns > 0 && layers > 0 && rows > 0 && radius > 0);
    HcpLattice lat;
    lat.radius = radius;
    lat.columns = columns;
    lat.layers = layers;
    lat.rows = rows;
    const double R = radius;
    const double layerStep = 2.0 * R * std::sqrt(2.0 / 3.0);
    const double rowStep = std::sqrt(3.0) * R;
    const std::size_t n = static_cast<std::size_t>(columns) * layers * rows;
    lat.positions.reserve(n);
    lat.rowOf.reserve(n);
    lat.layerOf.reserve(n);
    for (int r = 0; r < rows; ++r)
        for (int l = 0; l < layers; ++l)
            for (int c = 0; c < columns; ++c) {
                const double x = R * (1.0 + 2.0 * c + (r & 1) + (l & 1));
                const double y = R + l * layerStep;
                const double z = R + r * rowStep + ((l & 1) ? R / std::sqrt(3.0) : 0.0);
                lat.positions.push_back({x, y, z});
                lat.rowOf.push_back(r);
                lat.layerOf.push_back(l);
                for (int a = 0; a < 3; ++a)
                    lat.hi[a] = std::max(lat.hi[a], lat.positions.back()[a] + R);
            }

    // Neighbours lie within one row, one layer and two columns; test that stencil exactly.
    auto index = [&](int c, int l, int r) {
        return static_cast<std::uint32_t>((static_cast<std::size_t>(r) * layers + l) * columns + c);
    };
    const double want = 2.0 * R, tol = 1e-6 * R;
    for (int r = 0; r < rows; ++r)
        for (int l = 0; l < layers; ++l)
            for (int c = 0; c < columns; ++c) {
                const std::uint32_t i = index(c, l, r);
                std::vector<std::uint32_t> found;
                for (int dr = -1; dr <= 1; ++dr)
                    for (int dl = -1; dl <= 1; ++dl)
                        for (int dc = -2; dc <= 2; ++dc) {
                            const int rr = r + dr, ll = l + dl, cc = c + dc;
                            if (rr < 0 || rr >= rows || ll < 0 || ll >= layers || cc < 0 ||
                                cc >= columns)
                                continue;
                            const std::uint32_t j = index(cc, ll, rr);
                            if (j <= i)
                                continue;
                            const auto& p = lat.positions[i];
                            const auto& q = lat.positions[j];
                            const double d = std::sqrt((q[0] - p[0]) * (q[0] - p[0]) +
                                                       (q[1] - p[1]) * (q[1] - p[1]) +
                                                       (q[2] - p[2]) * (q[2] - p[2]));
                            if (std::fabs(d - want) < tol)
                                found.push_back(j);
                        }
                std::sort(found.begin(), found.end());
                for (std::uint32_t j : found)
                    lat.pairs.push_back({i, j});
            }
    return lat;
}

} // namespace faultline::core
