#include "core/surface/detail/plan_fold.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::core::detail {

namespace {

// The fold a cell passes to its children: the parent's, moved to this cell's centre, plus the
// spheres that are far from this cell. P: the kernel's power.
template <int P> Fold foldWith(const Fold& parent, const Box& box, float minD2) {
    Fold f;
    double half2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        f.centre[k] = 0.5 * (double(box.lo[k]) + double(box.hi[k]));
        const double e = 0.5 * (double(box.hi[k]) - double(box.lo[k]));
        half2 += e * e;
    }
    const double delta = std::sqrt(half2);
    f.value = parent.value;
    for (int k = 0; k < 3; ++k)
        f.value += parent.grad[k] * (f.centre[k] - parent.centre[k]);
    f.grad = parent.grad;
    f.remainder = parent.remainder;
    const double minD = std::sqrt(double(minD2));
    const double far = std::max(kFoldRatio * delta, delta + 2.0 * minD);
    const float far2 = static_cast<float>(far * far) * (1.0f + 1e-6f);
    const std::size_t n = parent.x.size();
    f.x.reserve(n), f.y.reserve(n), f.z.reserve(n), f.r.reserve(n);
    const float cx = float(f.centre[0]), cy = float(f.centre[1]), cz = float(f.centre[2]);
    double value = 0.0, gx = 0.0, gy = 0.0, gz = 0.0, rem = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const float fx = cx - parent.x[i], fy = cy - parent.y[i], fz = cz - parent.z[i];
        if (fx * fx + fy * fy + fz * fz < far2) {
            f.x.push_back(parent.x[i]), f.y.push_back(parent.y[i]), f.z.push_back(parent.z[i]);
            f.r.push_back(parent.r[i]);
            continue;
        }
        // w / d^p, its gradient -p w d^-(p+2) (x - c), and the Hessian's norm p (p+1) w d^-(p+2)
        // at distances of at least d - delta within the cell (in double: exact enough).
        const double dx = f.centre[0] - double(parent.x[i]), dy = f.centre[1] - double(parent.y[i]),
                     dz = f.centre[2] - double(parent.z[i]);
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double d = std::sqrt(d2);
        if (d - delta <= minD) { // rounding at the threshold: keep it in the list
            f.x.push_back(parent.x[i]), f.y.push_back(parent.y[i]), f.z.push_back(parent.z[i]);
            f.r.push_back(parent.r[i]);
            continue;
        }
        const double w = parent.r[i];
        const double inv = P == 1 ? 1.0 / d : 1.0 / d2;
        value += w * inv;
        const double g = -P * w * inv / d2;
        gx += g * dx, gy += g * dy, gz += g * dz;
        const double near = d - delta;
        const double nearP2 = P == 1 ? near * near * near : near * near * near * near;
        rem += w / nearP2;
    }
    f.value += value;
    f.grad[0] += gx, f.grad[1] += gy, f.grad[2] += gz;
    f.remainder += 0.5 * half2 * P * (P + 1) * rem;
    return f;
}

} // namespace

// Bounds of f over `box` from the parent's fold: the linear part's range over the box, the
// remainder, and every sphere left in the lists.
FieldBounds foldBounds(const Fold& fold, const Box& box, int power, float minD2) {
    double value = fold.value, spread = fold.remainder;
    for (int k = 0; k < 3; ++k) {
        const double c = 0.5 * (double(box.lo[k]) + double(box.hi[k]));
        const double e = 0.5 * (double(box.hi[k]) - double(box.lo[k]));
        value += fold.grad[k] * (c - fold.centre[k]);
        spread += std::abs(fold.grad[k]) * e;
    }
    // Double sums of a few thousand terms: a relative 1e-12 covers their rounding.
    spread += 1e-12 * std::abs(value) + 1e-300;
    FieldBounds b{value - spread, value + spread};
    addDirectBounds(power, fold.x.data(), fold.y.data(), fold.z.data(), fold.r.data(),
                    fold.x.size(), box, minD2, b.low, b.high);
    b.low = std::max(b.low, 0.0); // every term is positive
    return b;
}

Fold foldFor(const Fold& parent, const Box& box, int power, float minD2) {
    return power == 1 ? foldWith<1>(parent, box, minD2) : foldWith<2>(parent, box, minD2);
}

} // namespace faultline::core::detail
