#include "core/surface/metaball_reference.hpp"

#include "core/surface/metaball_kernel.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace faultline::core {

double meanRadius(const SphereSet& spheres) {
    if (spheres.size() == 0)
        return 0.0;
    double sum = 0.0;
    for (float r : spheres.radius)
        sum += r;
    return sum / static_cast<double>(spheres.size());
}

namespace {

// One sphere's term of the field, weight w at squared distance d2raw from the point: the term
// referenceSample and the wrapping iso's sums add (the same double in both).
template <MetaballKernel Kernel>
[[gnu::always_inline]] inline double termAt(double w, double d2raw, double minD2,
                                            float compactReach) {
    if constexpr (Kernel == MetaballKernel::InverseSquare) {
        return w / std::max(d2raw, minD2);
    } else if constexpr (Kernel == MetaballKernel::Inverse) {
        return w / std::sqrt(std::max(d2raw, minD2));
    } else {
        const double big = compactReach * w;
        const double t = 1.0 - d2raw / (big * big);
        return t > 0 ? w * t * t * t : 0.0; // adding +0 leaves a sum of positive terms as it is
    }
}

// The field at p by the direct sum: its value, gradient and colour.
FieldSample sampleAt(const SphereSet& s, const SurfaceParams& params, double minD2,
                     const std::array<double, 3>& p) {
    FieldSample out;
    double rgb[3] = {0, 0, 0};
    int colored = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double dx = p[0] - s.x[i], dy = p[1] - s.y[i], dz = p[2] - s.z[i];
        const double d2raw = dx * dx + dy * dy + dz * dz;
        const double d2 = std::max(d2raw, minD2);
        const double w = s.radius[i];
        double slope = 0.0; // d f_i / d(d^2)
        switch (params.kernel) {
        case MetaballKernel::InverseSquare:
            out.value += termAt<MetaballKernel::InverseSquare>(w, d2raw, minD2, 0.0f);
            slope = d2raw < minD2 ? 0.0 : -w / (d2 * d2);
            break;
        case MetaballKernel::Inverse:
            out.value += termAt<MetaballKernel::Inverse>(w, d2raw, minD2, 0.0f);
            slope = d2raw < minD2 ? 0.0 : -0.5 * w / (d2 * std::sqrt(d2));
            break;
        case MetaballKernel::Compact: {
            out.value += termAt<MetaballKernel::Compact>(w, d2raw, minD2, params.compactReach);
            const double big = params.compactReach * w;
            const double t = 1.0 - d2raw / (big * big);
            if (t > 0)
                slope = -3.0 * w * t * t / (big * big);
            break;
        }
        }
        out.gradient[0] += 2.0 * slope * dx;
        out.gradient[1] += 2.0 * slope * dy;
        out.gradient[2] += 2.0 * slope * dz;
        const double reach = s.radius[i] + params.colorReach;
        if (d2raw < reach * reach) {
            for (int c = 0; c < 3; ++c)
                rgb[c] += s.rgb.empty() ? 1.0 : s.rgb[3 * i + c];
            ++colored;
        }
    }
    for (int c = 0; c < 3; ++c)
        out.color[c] = colored ? static_cast<float>(rgb[c] / colored) : params.initialColor[c];
    return out;
}

double minDistance2(const SphereSet& s) {
    const double minD = kMinDistanceFactor * meanRadius(s);
    return minD * minD;
}

} // namespace

FieldSample referenceSample(const SphereSet& s, const SurfaceParams& params,
                            const std::array<double, 3>& p) {
    return sampleAt(s, params, minDistance2(s), p);
}

namespace {

// Algorithm 1's sum at one point: the value, and with Gradient its gradient (line 8) into g.
template <bool Gradient>
float algorithm1Point(const SphereSet& s, const SurfaceParams& params, const InverseKernel& inv,
                      float px, float py, float pz, float g[3]) {
    float f = 0.0f;
    for (std::size_t n = 0; n < s.size(); ++n) {
        const float dx = px - s.x[n], dy = py - s.y[n], dz = pz - s.z[n];
        const float d2 = dx * dx + dy * dy + dz * dz;
        float slope = 0.0f; // d f_n / d(d^2)
        if (params.kernel == MetaballKernel::Compact) {
            const float big = params.compactReach * s.radius[n];
            const float invR2 = 1.0f / (big * big);
            f += s.radius[n] * compactValue(d2, invR2);
            if constexpr (Gradient)
                slope = s.radius[n] * compactSlope(d2, invR2);
        } else {
            f += s.radius[n] * inv.value(d2);
            if constexpr (Gradient)
                slope = d2 < inv.minD2 ? 0.0f : s.radius[n] * inv.slope(d2);
        }
        if constexpr (Gradient) {
            g[0] += 2.0f * slope * dx;
            g[1] += 2.0f * slope * dy;
            g[2] += 2.0f * slope * dz;
        }
    }
    return f;
}

} // namespace

std::vector<float> algorithm1Dense(const SphereSet& s, const SurfaceParams& params,
                                   const std::array<int, 3>& origin, const std::array<int, 3>& dims,
                                   float h, std::vector<std::array<float, 3>>* gradient) {
    const std::size_t nx = dims[0], ny = dims[1], nz = dims[2];
    std::vector<float> field(nx * ny * nz, 0.0f);
    if (gradient)
        gradient->assign(field.size(), {0.0f, 0.0f, 0.0f});
    const float minD = kMinDistanceFactor * static_cast<float>(meanRadius(s));
    const InverseKernel inv{params.kernel == MetaballKernel::Inverse ? 1 : 2, minD * minD};
    tbb::parallel_for(std::size_t{0}, nz, [&](std::size_t k) {
        const float pz = (origin[2] + static_cast<int>(k)) * h;
        for (std::size_t j = 0; j < ny; ++j) {
            const float py = (origin[1] + static_cast<int>(j)) * h;
            const std::size_t row = (k * ny + j) * nx;
            for (std::size_t i = 0; i < nx; ++i) {
                const float px = (origin[0] + static_cast<int>(i)) * h;
                if (gradient)
                    field[row + i] = algorithm1Point<true>(s, params, inv, px, py, pz,
                                                           (*gradient)[row + i].data());
                else
                    field[row + i] = algorithm1Point<false>(s, params, inv, px, py, pz, nullptr);
            }
        }
    });
    return field;
}

namespace {

// The field's value at N points in one pass over the spheres, each point's terms added in the
// spheres' order: the same doubles as N calls of sampleAt, for a sixth of the passes over the
// spheres (and the points' divisions side by side).
template <MetaballKernel Kernel, std::size_t N>
void valuesAt(const SphereSet& s, float compactReach, double minD2,
              const std::array<std::array<double, 3>, N>& p, std::array<double, N>& out) {
    out.fill(0.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double x = s.x[i], y = s.y[i], z = s.z[i], w = s.radius[i];
        for (std::size_t n = 0; n < N; ++n) {
            const double dx = p[n][0] - x, dy = p[n][1] - y, dz = p[n][2] - z;
            out[n] += termAt<Kernel>(w, dx * dx + dy * dy + dz * dz, minD2, compactReach);
        }
    }
}

// Over `samples` spheres spread through the set: the lowest field value of the six points
// `reach` radii from the centre along the axes (the side where the field is lowest).
std::vector<double> lowestAround(const SphereSet& s, const SurfaceParams& params,
                                 std::size_t samples, double reach) {
    const std::size_t n = s.size();
    constexpr std::size_t kDirections = 6;
    const double minD2 = minDistance2(s);
    std::vector<double> lowest(samples, 0.0);
    tbb::parallel_for(std::size_t{0}, samples, [&](std::size_t q) {
        const std::size_t i = q * n / samples;
        std::array<std::array<double, 3>, kDirections> points;
        for (std::size_t d = 0; d < kDirections; ++d) {
            points[d] = {s.x[i], s.y[i], s.z[i]};
            points[d][d / 2] += (d % 2 ? -reach : reach) * s.radius[i];
        }
        std::array<double, kDirections> values;
        switch (params.kernel) {
        case MetaballKernel::InverseSquare:
            valuesAt<MetaballKernel::InverseSquare>(s, params.compactReach, minD2, points, values);
            break;
        case MetaballKernel::Inverse:
            valuesAt<MetaballKernel::Inverse>(s, params.compactReach, minD2, points, values);
            break;
        case MetaballKernel::Compact:
            valuesAt<MetaballKernel::Compact>(s, params.compactReach, minD2, points, values);
            break;
        }
        // As std::min from +inf: a NaN value (a sphere without a finite centre) is passed
        // over (all six: the sample counts as +inf), and the sort below never sees one.
        double low = std::numeric_limits<double>::infinity();
        for (double v : values)
            low = std::min(low, v);
        lowest[q] = low;
    });
    return lowest;
}

} // namespace

double wrappingIso(const SphereSet& s, const SurfaceParams& params) {
    const std::size_t n = s.size();
    if (n == 0)
        return 0.0;
    const std::size_t samples = std::min<std::size_t>(n, 96);
    std::vector<double> lowest = lowestAround(s, params, samples, 1.5);
    std::sort(lowest.begin(), lowest.end());
    return lowest[samples / 4];
}

std::array<double, 2> isoSliderRange(const SphereSet& s, const SurfaceParams& params) {
    const std::size_t n = s.size();
    if (n == 0)
        return {0.0, 0.0};
    // At most about 5e7 kernel evaluations (a tenth of a second), whatever the set's size.
    const std::size_t samples = std::clamp<std::size_t>(5'000'000 / n, std::min<std::size_t>(n, 8),
                                                        std::min<std::size_t>(n, 96));
    const std::vector<double> inner = lowestAround(s, params, samples, 0.5);
    const double high = *std::max_element(inner.begin(), inner.end());
    // The wrapping iso's own sample costs 600 x N: for large sets, two decades below `high`.
    const double low = n <= 50'000 ? wrappingIso(s, params) / 3.0 : high / 100.0;
    return {std::min(low, high), high};
}

} // namespace faultline::core
