// Metaball kernels as functions of squared distance, with the softened (smooth) versions that
// split a long-tailed kernel into an exact near part and smooth parts summed on coarser grids.
#pragma once

#include "core/surface/surface_params.hpp"

#include <cmath>

namespace faultline::core {

// Distances below this (in units of the mean radius) are clamped so f stays finite at centres;
// the reference (Algorithm 1) clamps the same way.
inline constexpr float kMinDistanceFactor = 1e-3f;

// Kernel k(d^2) for one unit-weight sphere; p = 1 (inverse) or 2 (inverse-square).
struct InverseKernel {
    int p = 2;
    float minD2 = 1e-8f;

    float value(float d2) const {
        d2 = d2 < minD2 ? minD2 : d2;
        return p == 2 ? 1.0f / d2 : 1.0f / std::sqrt(d2);
    }
    // dk/d(d^2): the gradient is 2 (x - c) times this.
    float slope(float d2) const {
        d2 = d2 < minD2 ? minD2 : d2;
        return p == 2 ? -1.0f / (d2 * d2) : -0.5f / (d2 * std::sqrt(d2));
    }
};

// gamma_a: equals the kernel for d >= a; inside, the order-4 Taylor polynomial of s^(-p/2) in
// s = d^2 / a^2 about s = 1, so gamma_a is C^4 and bounded. The multilevel sum uses
// k = (k - gamma_a0) + (gamma_a0 - gamma_a1) + ... + gamma_aL.
struct SoftenedKernel {
    int p = 2;
    float a2 = 1.0f;    // a^2
    float scale = 1.0f; // a^-p
    float coef[5] = {}; // binomial(-p/2, j)

    SoftenedKernel() = default;
    SoftenedKernel(int power, float a, int order = 4) : p(power), a2(a * a) {
        scale = power == 2 ? 1.0f / a2 : 1.0f / a;
        const double e = -0.5 * power;
        double c = 1.0;
        for (int j = 0; j < 5; ++j) {
            coef[j] = j <= order ? static_cast<float>(c) : 0.0f;
            c *= (e - j) / (j + 1);
        }
    }
    // Polynomial part, valid for d2 < a2.
    float inner(float d2) const {
        const float t = d2 / a2 - 1.0f;
        return scale * (coef[0] + t * (coef[1] + t * (coef[2] + t * (coef[3] + t * coef[4]))));
    }
    float innerSlope(float d2) const {
        const float t = d2 / a2 - 1.0f;
        return scale / a2 *
               (coef[1] + t * (2.0f * coef[2] + t * (3.0f * coef[3] + t * 4.0f * coef[4])));
    }
};

// Wyvill's compact kernel (1 - d^2/R^2)^3 for d < R, with invR2 = 1 / R^2.
inline float compactValue(float d2, float invR2) {
    const float t = 1.0f - d2 * invR2;
    return t > 0.0f ? t * t * t : 0.0f;
}
inline float compactSlope(float d2, float invR2) {
    const float t = 1.0f - d2 * invR2;
    return t > 0.0f ? -3.0f * t * t * invR2 : 0.0f;
}

} // namespace faultline::core
