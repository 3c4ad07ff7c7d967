#include "core/surface/detail/plan_fold.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::core::detail {

namespace {

// The fold's quadratic moved from its centre by d: value, gradient (the Hessian stays).
void moveQuadratic(const Fold& from, const std::array<double, 3>& d, double& value,
                   std::array<double, 3>& grad) {
    const auto& h = from.hess;
    const double hd[3] = {h[0] * d[0] + h[3] * d[1] + h[4] * d[2],
                          h[3] * d[0] + h[1] * d[1] + h[5] * d[2],
                          h[4] * d[0] + h[5] * d[1] + h[2] * d[2]};
    value = from.value;
    for (int k = 0; k < 3; ++k) {
        value += from.grad[k] * d[k] + 0.5 * hd[k] * d[k];
        grad[k] = from.grad[k] + hd[k];
    }
}

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
    moveQuadratic(parent,
                  {f.centre[0] - parent.centre[0], f.centre[1] - parent.centre[1],
                   f.centre[2] - parent.centre[2]},
                  f.value, f.grad);
    f.hess = parent.hess;
    f.remainder = parent.remainder;
    const double minD = std::sqrt(double(minD2));
    const double far = std::max(kFoldRatio * delta, delta + 2.0 * minD);
    const float far2 = static_cast<float>(far * far) * (1.0f + 1e-6f);
    const std::size_t n = parent.x.size();
    f.x.reserve(n), f.y.reserve(n), f.z.reserve(n), f.r.reserve(n);
    const float cx = float(f.centre[0]), cy = float(f.centre[1]), cz = float(f.centre[2]);
    double value = 0.0, gx = 0.0, gy = 0.0, gz = 0.0, rem = 0.0;
    double hxx = 0.0, hyy = 0.0, hzz = 0.0, hxy = 0.0, hxz = 0.0, hyz = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const float fx = cx - parent.x[i], fy = cy - parent.y[i], fz = cz - parent.z[i];
        if (fx * fx + fy * fy + fz * fz < far2) {
            f.x.push_back(parent.x[i]), f.y.push_back(parent.y[i]), f.z.push_back(parent.z[i]);
            f.r.push_back(parent.r[i]);
            continue;
        }
        // w / d^p with u = x - c: gradient -p w d^-(p+2) u, Hessian w (p (p+2) d^-(p+4) u u^T -
        // p d^-(p+2) I), and the third derivative along any direction at most p (p+1) (p+2) w
        // d^-(p+3) (its radial value), at distances of at least d - delta within the cell
        // (Taylor's remainder: a sixth of that times delta^3). In double: exact enough.
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
        const double q = P * (P + 2) * w * inv / (d2 * d2);
        hxx += q * dx * dx + g, hyy += q * dy * dy + g, hzz += q * dz * dz + g;
        hxy += q * dx * dy, hxz += q * dx * dz, hyz += q * dy * dz;
        const double near = d - delta, near2 = near * near;
        const double nearP3 = P == 1 ? near2 * near2 : near2 * near2 * near;
        rem += w / nearP3;
    }
    f.value += value;
    f.grad[0] += gx, f.grad[1] += gy, f.grad[2] += gz;
    f.hess[0] += hxx, f.hess[1] += hyy, f.hess[2] += hzz;
    f.hess[3] += hxy, f.hess[4] += hxz, f.hess[5] += hyz;
    f.remainder += half2 * delta / 6.0 * P * (P + 1) * (P + 2) * rem;
    return f;
}

} // namespace

// Bounds of f over `box` from the parent's fold: the linear part's range over the box, the
// remainder, and every sphere left in the lists.
FieldBounds foldBounds(const Fold& fold, const Box& box, int power, float minD2) {
    std::array<double, 3> d, e, grad;
    for (int k = 0; k < 3; ++k) {
        d[k] = 0.5 * (double(box.lo[k]) + double(box.hi[k])) - fold.centre[k];
        e[k] = 0.5 * (double(box.hi[k]) - double(box.lo[k]));
    }
    double value = 0.0;
    moveQuadratic(fold, d, value, grad);
    // Over the box, u = x - centre with |u_k| <= e_k: |g.u| <= sum |g_k| e_k and
    // |u^T H u| / 2 <= sum_kl |H_kl| e_k e_l / 2.
    const auto& h = fold.hess;
    double spread = fold.remainder;
    for (int k = 0; k < 3; ++k)
        spread += std::abs(grad[k]) * e[k];
    spread += 0.5 * (std::abs(h[0]) * e[0] * e[0] + std::abs(h[1]) * e[1] * e[1] +
                     std::abs(h[2]) * e[2] * e[2]) +
              std::abs(h[3]) * e[0] * e[1] + std::abs(h[4]) * e[0] * e[2] +
              std::abs(h[5]) * e[1] * e[2];
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
