#include "core/surface/detail/plan_fold.hpp"

#include "core/util/simd8.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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

// Sums of the folded spheres' terms about a centre, and what bounds their rounding.
struct FoldSums {
    double value = 0.0, grad[3] = {0, 0, 0}, hess[6] = {0, 0, 0, 0, 0, 0}, remainder = 0.0;
    double gradAbs = 0.0, hessAbs = 0.0; // sums of |gradient| and of Hessian norms
};

// Over the spheres within sqrt(far2) of c no term (they are flagged in `near`, 1 each, and
// counted in the return value); over the others, with u = c - sphere and weight w: w / d^p, its
// gradient -p w d^-(p+2) u, Hessian w (p (p+2) d^-(p+4) u u^T - p d^-(p+2) I), and
// w / (d - delta)^(p+3) for the remainder; eight at a time in float (the caller widens by their
// rounding). One pass: the far spheres are never copied.
template <int P>
[[gnu::always_inline]] inline std::size_t
foldTermsBody(const float* px, const float* py, const float* pz, const float* pr, std::size_t n,
              float cx, float cy, float cz, float far2, float delta, unsigned char* near,
              FoldSums& out) {
    using simd8::splat;
    using simd8::v8f;
    v8f value{}, gx{}, gy{}, gz{}, hxx{}, hyy{}, hzz{}, hxy{}, hxz{}, hyz{}, rem{}, gAbs{}, hAbs{};
    const v8f vdelta = splat(delta), one = splat(1.0f), vfar2 = splat(far2);
    // Near spheres and padding lanes: weight 0 at a distance of 1 + delta (finite terms).
    const v8f padX = splat(1.0f + delta);
    const v8f vcx = splat(cx), vcy = splat(cy), vcz = splat(cz);
    std::size_t kept = 0;
    for (std::size_t q = 0; q < n; q += 8) {
        const std::size_t left = n - q;
        v8f x = vcx - simd8::loadUpTo(px + q, left), y = vcy - simd8::loadUpTo(py + q, left),
            z = vcz - simd8::loadUpTo(pz + q, left), wt = simd8::loadUpTo(pr + q, left);
        auto drop = x * x + y * y + z * z < vfar2; // near: listed, not folded
        for (std::size_t l = 0; l < 8 && l < left; ++l) {
            near[q + l] = drop[l] ? 1 : 0;
            kept += near[q + l];
        }
        for (std::size_t l = left; l < 8; ++l)
            drop[l] = -1; // padding
        x = drop ? padX : x, y = drop ? v8f{} : y, z = drop ? v8f{} : z, wt = drop ? v8f{} : wt;
        const v8f d2 = x * x + y * y + z * z;
        const v8f invd = simd8::inverseSqrt(d2);
        const v8f invd2 = invd * invd;
        const v8f inv = P == 1 ? invd : invd2; // d^-p
        const v8f wi = wt * inv;
        value += wi;
        const v8f g = splat(-float(P)) * wi * invd2;
        gx += g * x, gy += g * y, gz += g * z;
        gAbs += splat(float(P)) * wi * invd;
        const v8f qq = splat(float(P * (P + 2))) * wi * invd2 * invd2;
        hxx += qq * x * x + g, hyy += qq * y * y + g, hzz += qq * z * z + g;
        hxy += qq * x * y, hxz += qq * x * z, hyz += qq * y * z;
        hAbs += splat(float(P * (P + 1))) * wi * invd2;
        const v8f nearD = d2 * invd - vdelta;
        const v8f nearD2 = nearD * nearD;
        const v8f nearP3 = P == 1 ? nearD2 * nearD2 : nearD2 * nearD2 * nearD;
        rem += wt * (one / nearP3);
    }
    out.value = simd8::sum(value);
    out.grad[0] = simd8::sum(gx), out.grad[1] = simd8::sum(gy), out.grad[2] = simd8::sum(gz);
    out.hess[0] = simd8::sum(hxx), out.hess[1] = simd8::sum(hyy), out.hess[2] = simd8::sum(hzz);
    out.hess[3] = simd8::sum(hxy), out.hess[4] = simd8::sum(hxz), out.hess[5] = simd8::sum(hyz);
    out.remainder = simd8::sum(rem);
    out.gradAbs = simd8::sum(gAbs), out.hessAbs = simd8::sum(hAbs);
    return kept;
}

FAULTLINE_HOT std::size_t foldTerms1(const float* px, const float* py, const float* pz,
                                     const float* pr, std::size_t n, float cx, float cy, float cz,
                                     float far2, float delta, unsigned char* near, FoldSums& out) {
    return foldTermsBody<1>(px, py, pz, pr, n, cx, cy, cz, far2, delta, near, out);
}
FAULTLINE_HOT std::size_t foldTerms2(const float* px, const float* py, const float* pz,
                                     const float* pr, std::size_t n, float cx, float cy, float cz,
                                     float far2, float delta, unsigned char* near, FoldSums& out) {
    return foldTermsBody<2>(px, py, pz, pr, n, cx, cy, cz, far2, delta, near, out);
}

// The fold a cell passes to its children: the parent's, moved to this cell's centre, plus the
// spheres that are far from this cell. P: the kernel's power.
template <int P> Fold foldWith(const Fold& parent, const Box& box, float minD2) {
    Fold f;
    double half2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        // The centre in float: the spheres' offsets from it are then the float differences.
        f.centre[k] = double(0.5f * (box.lo[k] + box.hi[k]));
        const double e = std::max(f.centre[k] - double(box.lo[k]), double(box.hi[k]) - f.centre[k]);
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
    // Far: at least kFoldRatio half-diagonals, and (rounding aside) well clear of the cell.
    const double far = std::max(kFoldRatio * delta, delta + 2.0 * minD) * (1.0 + 1e-5);
    const float far2 = static_cast<float>(far * far);
    const std::size_t n = parent.x.size();
    const float cx = float(f.centre[0]), cy = float(f.centre[1]), cz = float(f.centre[2]);
    // One pass folds the far spheres and flags the near ones; then lists of exactly the near
    // spheres (a fold per straddling cell: reserving the parent's size churned pages).
    thread_local std::vector<unsigned char> near;
    near.resize(n);
    FoldSums sums;
    const std::size_t kept = (P == 1 ? foldTerms1 : foldTerms2)(
        parent.x.data(), parent.y.data(), parent.z.data(), parent.r.data(), n, cx, cy, cz, far2,
        static_cast<float>(delta), near.data(), sums);
    f.x.resize(kept), f.y.resize(kept), f.z.resize(kept), f.r.resize(kept);
    std::size_t a = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (near[i]) {
            f.x[a] = parent.x[i], f.y[a] = parent.y[i], f.z[a] = parent.z[i];
            f.r[a] = parent.r[i];
            ++a;
        }
    if (kept == n)
        return f;
    f.value += sums.value;
    for (int k = 0; k < 3; ++k)
        f.grad[k] += sums.grad[k];
    for (int k = 0; k < 6; ++k)
        f.hess[k] += sums.hess[k];
    // Float terms and sums: each within a relative 1e-6 (a few roundings, the per-lane sums
    // over at most a few thousand terms within 1e-4); 1e-3 of every part's size over the cell
    // bounds what rounding moved, and the remainder is widened by as much.
    const double rounding = 1e-3 * (sums.value + delta * sums.gradAbs + half2 * sums.hessAbs + 0.0);
    f.remainder +=
        (1.0 + 1e-3) * half2 * delta / 6.0 * P * (P + 1) * (P + 2) * sums.remainder + rounding;
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
