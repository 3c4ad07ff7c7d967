// PlaneFit: best-fit plane of points by principal components, and its geological orientation.
// +x east, +y north, +z up; dip 0-90 below horizontal; dip direction clockwise from north, 0-360.
#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace faultline::core {

using Vec3d = std::array<double, 3>;
using Mat3d = std::array<std::array<double, 3>, 3>;

// Eigen decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations (robust for
// repeated and tiny eigenvalues). values ascending; vectors[i] is the unit eigenvector of
// values[i].
struct SymmetricEigen3 {
    Vec3d values{0, 0, 0};
    std::array<Vec3d, 3> vectors{};
};
SymmetricEigen3 eigenSymmetric3(const Mat3d& m);

// Orientation in degrees. strike = dipDirection - 90 (right-hand rule), 0-360. A horizontal
// plane has dip 0 and, by convention, dipDirection 0 (strike 270).
struct PlaneOrientation {
    double dip = 0;
    double dipDirection = 0;
    double strike = 0;
};

// The same plane's normal with one sign chosen: upward (nz > 0); for a vertical plane
// (|nz| <= 1e-12 |n|) the sign that puts the dip direction in [0, 180). Unit length.
// A zero or non-finite normal comes back as NaNs.
Vec3d canonicalNormal(const Vec3d& normal);
// Orientation of the plane with this normal (any sign, any nonzero length).
PlaneOrientation orientationFromNormal(const Vec3d& normal);
// Unit upward normal of the plane with this dip and dip direction (degrees).
Vec3d normalFromOrientation(double dipDegrees, double dipDirectionDegrees);
// Horizontal unit vector along strike, and the unit down-dip vector in the plane, of a plane
// with this (canonical) normal; for a horizontal plane strike is west (-x) and down-dip north.
Vec3d strikeVector(const Vec3d& canonical);
Vec3d downDipVector(const Vec3d& canonical);

struct PlaneFit {
    bool valid = false; // >= 3 points and a unique smallest eigenvalue direction
    std::size_t count = 0;
    Vec3d centroid{0, 0, 0};
    Vec3d normal{0, 0, 0};      // canonical; eigenvector of the smallest covariance eigenvalue
    Vec3d eigenvalues{0, 0, 0}; // of the population covariance, ascending
    PlaneOrientation orientation;
};

// Least-squares plane (orthogonal distances) through the points: centroid, covariance
// (two-pass, so large coordinate offsets do not cost precision), smallest eigenvector.
// Invalid (NaN orientation) when fewer than 3 points or when the two smallest eigenvalues
// are equal within 1e-9 of the largest (a line or a point: the normal is not determined).
// `containsAxis` (0 x, 1 y, 2 z): the plane is made to contain that axis direction (its normal
// has no component along it): for section models, thin along one axis, where the thinnest
// spread of a fault's spheres is the model's own thickness, not the fault's.
PlaneFit fitPlane(std::span<const Vec3d> points, int containsAxis = -1);
// The principal axes of a covariance as fitPlane takes them (values ascending, vectors[0] the
// normal): with `containsAxis`, that axis is made the largest (a stand-in value) and uncoupled,
// so the normal and values[0..1] lie in the plane of the other two axes.
SymmetricEigen3 planeAxes(Mat3d covariance, int containsAxis = -1);

// The axis a model is thin along (extent below `ratio` of its largest extent), or -1: such a
// model is a section, and faults in it are planes containing that axis.
int sectionAxis(const Vec3d& extent, double ratio = 0.1);
// The same for a model of spheres of this mean diameter: also an axis only a few spheres thick
// (3 to 8 diameters: one tilted layer may be the fault itself) and under a quarter of the largest
// extent, as fault candidates' network method orients them (a granular sandbox a few grains deep,
// periodic or between walls). Stable through a run, where the ratio alone flips as the model
// stretches.
int sectionAxisOfSpheres(const Vec3d& extent, double meanDiameter);

} // namespace faultline::core
