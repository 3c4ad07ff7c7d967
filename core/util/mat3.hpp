// 3 x 3 matrices of doubles: the determinant and the inverse by cofactors, shared by the two
// strain computations (core/synth/local_strain, core/motion/strain_from_motion).
#pragma once

#include <array>
#include <cmath>

namespace faultline::core {

using Mat3d = std::array<std::array<double, 3>, 3>;

inline double determinant3(const Mat3d& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// out = m^-1 by cofactors (one division); false, `out` untouched, when |det m| is not above
// `minDeterminant` (the caller's "nearly singular", relative to its matrix's scale) or is NaN.
inline bool invert3(const Mat3d& m, double minDeterminant, Mat3d& out) {
    const double d = determinant3(m);
    if (!(std::fabs(d) > minDeterminant))
        return false;
    const double k = 1.0 / d;
    out[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * k;
    out[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * k;
    out[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * k;
    out[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * k;
    out[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * k;
    out[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * k;
    out[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * k;
    out[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * k;
    out[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * k;
    return true;
}

} // namespace faultline::core
