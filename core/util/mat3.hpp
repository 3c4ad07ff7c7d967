// 3 x 3 matrices of doubles: the determinant and the inverse by cofactors, shared by the two
// strain computations (core/synth/local_strain, core/motion/strain_from_motion).
#pragma once

#include <array>
#include <cmath>

namespace faultline::core {

using Mat3d = std::array<std::array<double, 3>, 3>;

// M: Mat3d, or a 3 x 3 array of any number type (strain's vector solves use vectors of four or
// eight doubles and get, lane by lane, the same values as on doubles). Results go to out
// parameters: a vector returned from a function outside the caller's AVX target would change
// the ABI (clang refuses it).
template <typename M, typename T> void determinant3(const M& m, T& out) {
    out = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

inline double determinant3(const Mat3d& m) {
    double d;
    determinant3(m, d);
    return d;
}

// out = the cofactors of m, transposed, times k (with k = 1 / det m: the inverse).
template <typename M, typename T> void scaledAdjugate3(const M& m, const T& k, M& out) {
    out[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * k;
    out[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * k;
    out[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * k;
    out[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * k;
    out[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * k;
    out[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * k;
    out[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * k;
    out[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * k;
    out[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * k;
}

// out = m^-1 by cofactors (one division); false, `out` untouched, when |det m| is not above
// `minDeterminant` (the caller's "nearly singular", relative to its matrix's scale) or is NaN.
inline bool invert3(const Mat3d& m, double minDeterminant, Mat3d& out) {
    const double d = determinant3(m);
    if (!(std::fabs(d) > minDeterminant))
        return false;
    scaledAdjugate3(m, 1.0 / d, out);
    return true;
}

} // namespace faultline::core
