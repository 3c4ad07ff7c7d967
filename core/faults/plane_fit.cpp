#include "core/faults/plane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace faultline::core {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double wrapDegrees(double a) {
    double w = std::fmod(a, 360.0);
    if (w < 0)
        w += 360.0;
    if (w >= 360.0) // fmod of a tiny negative number plus 360 can round up to 360
        w -= 360.0;
    return w;
}
} // namespace

SymmetricEigen3 eigenSymmetric3(const Mat3d& m) {
    Mat3d a = m;
    Mat3d v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    double scale = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            scale = std::max(scale, std::fabs(a[i][j]));
    constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int sweep = 0; sweep < 64 && scale > 0; ++sweep) {
        const double off = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
        if (off == 0.0)
            break;
        for (const auto& pq : kPairs) {
            const int p = pq[0], q = pq[1];
            const double apq = a[p][q];
            // Below this an element moves eigenvalues by < 1e-36 of the matrix scale.
            if (std::fabs(apq) <= 1e-18 * scale) {
                a[p][q] = a[q][p] = 0;
                continue;
            }
            const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            const double t =
                (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::hypot(theta, 1.0));
            const double c = 1.0 / std::sqrt(t * t + 1.0);
            const double s = t * c;
            for (int k = 0; k < 3; ++k) { // A <- A J
                const double akp = a[k][p], akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for (int k = 0; k < 3; ++k) { // A <- J^T A
                const double apk = a[p][k], aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            a[p][q] = a[q][p] = 0;
            for (int k = 0; k < 3; ++k) { // V <- V J
                const double vkp = v[k][p], vkq = v[k][q];
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return a[i][i] < a[j][j]; });
    SymmetricEigen3 result;
    for (int r = 0; r < 3; ++r) {
        const int i = order[r];
        result.values[r] = a[i][i];
        Vec3d vec{v[0][i], v[1][i], v[2][i]};
        const double len = std::sqrt(vec[0] * vec[0] + vec[1] * vec[1] + vec[2] * vec[2]);
        for (double& c : vec)
            c /= len;
        result.vectors[r] = vec;
    }
    return result;
}

Vec3d canonicalNormal(const Vec3d& normal) {
    const double len =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(len > 0) || !std::isfinite(len))
        return {kNaN, kNaN, kNaN};
    Vec3d n{normal[0] / len, normal[1] / len, normal[2] / len};
    bool flip;
    if (std::fabs(n[2]) > 1e-12)
        flip = n[2] < 0;
    else // vertical: dip direction atan2(nx, ny) in [0, 180)
        flip = n[0] < 0 || (n[0] == 0 && n[1] < 0);
    if (flip)
        for (double& c : n)
            c = -c;
    if (std::fabs(n[2]) <= 1e-12)
        n[2] = 0;
    return n;
}

PlaneOrientation orientationFromNormal(const Vec3d& normal) {
    const Vec3d n = canonicalNormal(normal);
    if (std::isnan(n[0]))
        return {kNaN, kNaN, kNaN};
    const double horizontal = std::hypot(n[0], n[1]);
    PlaneOrientation o;
    o.dip = std::atan2(horizontal, n[2]) * kDegPerRad;
    o.dipDirection = horizontal > 0 ? wrapDegrees(std::atan2(n[0], n[1]) * kDegPerRad) : 0.0;
    o.strike = wrapDegrees(o.dipDirection - 90.0);
    return o;
}

Vec3d normalFromOrientation(double dipDegrees, double dipDirectionDegrees) {
    const double dip = dipDegrees / kDegPerRad, dd = dipDirectionDegrees / kDegPerRad;
    return {std::sin(dip) * std::sin(dd), std::sin(dip) * std::cos(dd), std::cos(dip)};
}

Vec3d strikeVector(const Vec3d& canonical) {
    const double h = std::hypot(canonical[0], canonical[1]);
    if (!(h > 0))
        return {-1, 0, 0}; // strike 270 for dip direction 0
    // strike azimuth = dip direction - 90: rotate the horizontal dip direction (nx, ny)/h
    // by 90 degrees counter-clockwise (seen from above).
    return {-canonical[1] / h, canonical[0] / h, 0};
}

Vec3d downDipVector(const Vec3d& canonical) {
    // In the plane, perpendicular to strike, pointing down: n x strike has z = -h.
    const Vec3d s = strikeVector(canonical);
    const Vec3d& n = canonical;
    Vec3d d{n[1] * s[2] - n[2] * s[1], n[2] * s[0] - n[0] * s[2], n[0] * s[1] - n[1] * s[0]};
    if (d[2] > 0 || (d[2] == 0 && std::hypot(n[0], n[1]) == 0 && d[1] < 0))
        for (double& c : d)
            c = -c;
    return d;
}

int sectionAxis(const Vec3d& extent, double ratio) {
    const double largest = std::max({extent[0], extent[1], extent[2]});
    int thin = -1;
    for (int a = 0; a < 3; ++a)
        if (extent[a] < ratio * largest && (thin < 0 || extent[a] < extent[thin]))
            thin = a;
    return largest > 0 ? thin : -1;
}

int sectionAxisOfSpheres(const Vec3d& extent, double meanDiameter) {
    if (const int thin = sectionAxis(extent); thin >= 0)
        return thin;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (extent[a] < extent[axis])
            axis = a;
    const double longest = std::max({extent[0], extent[1], extent[2]});
    // At least 3 diameters: a single (perhaps tilted) layer of spheres may be the fault itself.
    return meanDiameter > 0 && extent[axis] >= 3.0 * meanDiameter &&
                   extent[axis] < 8.0 * meanDiameter && extent[axis] < 0.25 * longest
               ? axis
               : -1;
}

SymmetricEigen3 planeAxes(Mat3d cov, int containsAxis) {
    if (containsAxis >= 0 && containsAxis < 3) {
        // The axis becomes the direction of the largest spread, uncoupled from the others, so
        // the smallest eigenvector (the normal) lies in the plane of the other two axes.
        const int a = containsAxis;
        const double trace = cov[0][0] + cov[1][1] + cov[2][2];
        for (int i = 0; i < 3; ++i)
            cov[a][i] = cov[i][a] = 0.0;
        cov[a][a] = 4.0 * trace + 1.0;
    }
    return eigenSymmetric3(cov);
}

PlaneFit fitPlane(std::span<const Vec3d> points, int containsAxis) {
    PlaneFit fit;
    fit.count = points.size();
    fit.centroid = {kNaN, kNaN, kNaN};
    fit.normal = {kNaN, kNaN, kNaN};
    fit.eigenvalues = {kNaN, kNaN, kNaN};
    fit.orientation = {kNaN, kNaN, kNaN};
    if (points.empty())
        return fit;
    Vec3d mean{0, 0, 0};
    for (const auto& p : points)
        for (int a = 0; a < 3; ++a)
            mean[a] += p[a];
    for (double& m : mean)
        m /= static_cast<double>(points.size());
    fit.centroid = mean;
    if (points.size() < 3)
        return fit;
    Mat3d cov{};
    for (const auto& p : points) {
        const double d[3] = {p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
        for (int i = 0; i < 3; ++i)
            for (int j = i; j < 3; ++j)
                cov[i][j] += d[i] * d[j];
    }
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) {
            cov[i][j] /= static_cast<double>(points.size());
            cov[j][i] = cov[i][j];
        }
    const bool section = containsAxis >= 0 && containsAxis < 3;
    const double axisVariance = section ? cov[containsAxis][containsAxis] : -1.0;
    const SymmetricEigen3 eig = planeAxes(cov, containsAxis);
    fit.eigenvalues = eig.values;
    if (axisVariance >= 0.0) { // report the real spread along the axis, not the stand-in
        fit.eigenvalues[2] = axisVariance;
        std::sort(fit.eigenvalues.begin(), fit.eigenvalues.end());
    }
    const double largest = eig.values[2];
    if (!(largest > 0) || !(eig.values[1] - eig.values[0] > 1e-9 * largest))
        return fit;
    fit.valid = true;
    fit.normal = canonicalNormal(eig.vectors[0]);
    fit.orientation = orientationFromNormal(fit.normal);
    return fit;
}

} // namespace faultline::core
