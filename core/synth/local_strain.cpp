#include "core/synth/local_strain.hpp"

#include "core/util/mat3.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace faultline::core {

namespace {

// Inverse by cofactors; false when (nearly) singular relative to the matrix scale.
bool invert(const Mat3d& m, Mat3d& out) {
    double scale = 0;
    for (const auto& row : m)
        for (double v : row)
            scale = std::max(scale, std::fabs(v));
    return invert3(m, 1e-9 * scale * scale * scale, out);
}

} // namespace

NeighbourTable neighbourTableFromPairs(std::size_t sphereCount,
                                       const std::vector<std::array<std::uint32_t, 2>>& pairs) {
    NeighbourTable t;
    t.offsets.assign(sphereCount + 1, 0);
    for (const auto& p : pairs) {
        assert(p[0] < sphereCount && p[1] < sphereCount);
        ++t.offsets[p[0] + 1];
        ++t.offsets[p[1] + 1];
    }
    for (std::size_t i = 0; i < sphereCount; ++i)
        t.offsets[i + 1] += t.offsets[i];
    t.partners.resize(t.offsets.back());
    std::vector<std::uint32_t> fill(t.offsets.begin(), t.offsets.end() - 1);
    for (const auto& p : pairs) {
        t.partners[fill[p[0]]++] = p[1];
        t.partners[fill[p[1]]++] = p[0];
    }
    for (std::size_t i = 0; i < sphereCount; ++i)
        std::sort(t.partners.begin() + t.offsets[i], t.partners.begin() + t.offsets[i + 1]);
    return t;
}

std::vector<double> vonMisesShearStrain(const std::vector<std::array<double, 3>>& initial,
                                        const std::vector<std::array<double, 3>>& current,
                                        const NeighbourTable& neighbours) {
    assert(initial.size() == current.size());
    assert(neighbours.offsets.size() == initial.size() + 1);
    std::vector<double> out(initial.size(), 0.0);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, initial.size(), 1024), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                Mat3d xx{}, yx{};
                for (std::uint32_t k = neighbours.offsets[i]; k < neighbours.offsets[i + 1]; ++k) {
                    const std::uint32_t j = neighbours.partners[k];
                    double X[3], Y[3];
                    for (int a = 0; a < 3; ++a) {
                        X[a] = initial[j][a] - initial[i][a];
                        Y[a] = current[j][a] - current[i][a];
                    }
                    for (int a = 0; a < 3; ++a)
                        for (int b = 0; b < 3; ++b) {
                            xx[a][b] += X[a] * X[b];
                            yx[a][b] += Y[a] * X[b];
                        }
                }
                Mat3d xxInv;
                if (!invert(xx, xxInv))
                    continue;
                Mat3d F{};
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        for (int c = 0; c < 3; ++c)
                            F[a][b] += yx[a][c] * xxInv[c][b];
                Mat3d E{};
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) {
                        double ftf = 0;
                        for (int c = 0; c < 3; ++c)
                            ftf += F[c][a] * F[c][b];
                        E[a][b] = 0.5 * (ftf - (a == b ? 1.0 : 0.0));
                    }
                const double dxy = E[0][0] - E[1][1], dyz = E[1][1] - E[2][2],
                             dzx = E[2][2] - E[0][0];
                out[i] = std::sqrt(E[0][1] * E[0][1] + E[1][2] * E[1][2] + E[0][2] * E[0][2] +
                                   (dxy * dxy + dyz * dyz + dzx * dzx) / 6.0);
            }
        });
    return out;
}

} // namespace faultline::core
