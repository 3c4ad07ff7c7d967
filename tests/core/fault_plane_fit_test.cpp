#include "core/faults/plane_fit.hpp"

#include "fault_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace faultline::core;
using faultline::core::testing::angleDiff;
using faultline::core::testing::dot3;

namespace {
Mat3d rotated(const Vec3d& diag, const std::array<Vec3d, 3>& axes) {
    Mat3d m{};
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                m[i][j] += diag[k] * axes[k][i] * axes[k][j];
    return m;
}
} // namespace

TEST(PlaneFit, EigenOfDiagonalMatrixIsSortedAscending) {
    const SymmetricEigen3 e = eigenSymmetric3({{{3, 0, 0}, {0, 1, 0}, {0, 0, 2}}});
    EXPECT_EQ(e.values, (Vec3d{1, 2, 3}));
    EXPECT_EQ(std::fabs(e.vectors[0][1]), 1.0);
    EXPECT_EQ(std::fabs(e.vectors[1][2]), 1.0);
    EXPECT_EQ(std::fabs(e.vectors[2][0]), 1.0);
}

TEST(PlaneFit, EigenOfRotatedMatrixRecoversAxes) {
    const double s = 1 / std::sqrt(2.0), t = 1 / std::sqrt(3.0), u = 1 / std::sqrt(6.0);
    const std::array<Vec3d, 3> axes{Vec3d{s, -s, 0}, Vec3d{t, t, t}, Vec3d{u, u, -2 * u}};
    const SymmetricEigen3 e = eigenSymmetric3(rotated({1e-6, 5, 40}, axes));
    EXPECT_NEAR(e.values[0], 1e-6, 1e-12);
    EXPECT_NEAR(e.values[1], 5, 1e-12);
    EXPECT_NEAR(e.values[2], 40, 1e-12);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(std::fabs(dot3(e.vectors[k], axes[k])), 1.0, 1e-12) << k;
}

TEST(PlaneFit, EigenOfRepeatedEigenvaluesGivesAnOrthonormalBasis) {
    const SymmetricEigen3 e = eigenSymmetric3({{{2, 1, 1}, {1, 2, 1}, {1, 1, 2}}}); // 1, 1, 4
    EXPECT_NEAR(e.values[0], 1, 1e-12);
    EXPECT_NEAR(e.values[1], 1, 1e-12);
    EXPECT_NEAR(e.values[2], 4, 1e-12);
    EXPECT_NEAR(dot3(e.vectors[0], e.vectors[1]), 0, 1e-12);
    EXPECT_NEAR(dot3(e.vectors[0], e.vectors[2]), 0, 1e-12);
    EXPECT_NEAR(dot3(e.vectors[1], e.vectors[2]), 0, 1e-12);
}

TEST(PlaneFit, OrientationOfKnownNormals) {
    PlaneOrientation o = orientationFromNormal({0, 0, 1});
    EXPECT_EQ(o.dip, 0);
    EXPECT_EQ(o.dipDirection, 0);
    EXPECT_EQ(o.strike, 270);

    o = orientationFromNormal({0, 0, -2}); // sign and length do not matter
    EXPECT_EQ(o.dip, 0);

    const double h = std::sin(std::numbers::pi / 6), v = std::cos(std::numbers::pi / 6);
    o = orientationFromNormal({h, 0, v}); // dips 30 degrees east
    EXPECT_NEAR(o.dip, 30, 1e-12);
    EXPECT_NEAR(o.dipDirection, 90, 1e-12);
    EXPECT_NEAR(o.strike, 0, 1e-12);

    o = orientationFromNormal({0, h, -v}); // downward normal of a plane dipping 30 south
    EXPECT_NEAR(o.dip, 30, 1e-12);
    EXPECT_NEAR(o.dipDirection, 180, 1e-12);
    EXPECT_NEAR(o.strike, 90, 1e-12);

    o = orientationFromNormal({-h, h, v}); // north-west
    EXPECT_NEAR(o.dipDirection, 315, 1e-12);
    EXPECT_NEAR(o.strike, 225, 1e-12);
}

TEST(PlaneFit, VerticalPlanesTakeTheDipDirectionBelow180) {
    PlaneOrientation o = orientationFromNormal({-1, 0, 0});
    EXPECT_EQ(o.dip, 90);
    EXPECT_EQ(o.dipDirection, 90);
    o = orientationFromNormal({0, -1, 0});
    EXPECT_EQ(o.dipDirection, 0);
    o = orientationFromNormal({-1, 1, 0});
    EXPECT_NEAR(o.dipDirection, 135, 1e-12);
}

TEST(PlaneFit, OrientationRoundTripsThroughTheNormal) {
    for (double dip : {0.5, 10.0, 45.0, 80.0, 89.9})
        for (double dd : {0.0, 0.25, 45.0, 179.0, 181.0, 270.0, 359.75}) {
            const PlaneOrientation o = orientationFromNormal(normalFromOrientation(dip, dd));
            EXPECT_NEAR(o.dip, dip, 1e-9);
            EXPECT_NEAR(angleDiff(o.dipDirection, dd), 0, 1e-9) << dip << " " << dd;
            EXPECT_GE(o.dipDirection, 0);
            EXPECT_LT(o.dipDirection, 360);
        }
}

TEST(PlaneFit, StrikeAndDownDipVectors) {
    const Vec3d n = normalFromOrientation(30, 90); // dips east
    const Vec3d s = strikeVector(n), d = downDipVector(n);
    EXPECT_NEAR(s[1], 1, 1e-12); // strike north (right-hand rule)
    EXPECT_NEAR(d[0], std::cos(std::numbers::pi / 6), 1e-12);
    EXPECT_NEAR(d[2], -0.5, 1e-12);
    EXPECT_NEAR(dot3(d, n), 0, 1e-12);
    EXPECT_NEAR(dot3(s, n), 0, 1e-12);
    const Vec3d flat = downDipVector({0, 0, 1});
    EXPECT_EQ(flat, (Vec3d{0, 1, 0}));
}

TEST(PlaneFit, FitsPointsOnATiltedPlaneExactly) {
    const Vec3d n = normalFromOrientation(30, 120);
    const Vec3d s = strikeVector(n), d = downDipVector(n);
    std::vector<Vec3d> pts;
    for (int i = -3; i <= 3; ++i)
        for (int j = -2; j <= 4; ++j)
            pts.push_back(
                {100 + i * s[0] + j * d[0], -50 + i * s[1] + j * d[1], 7 + i * s[2] + j * d[2]});
    const PlaneFit fit = fitPlane(pts);
    ASSERT_TRUE(fit.valid);
    EXPECT_EQ(fit.count, pts.size());
    EXPECT_NEAR(fit.orientation.dip, 30, 1e-9);
    EXPECT_NEAR(fit.orientation.dipDirection, 120, 1e-9);
    EXPECT_NEAR(fit.orientation.strike, 30, 1e-9);
    EXPECT_NEAR(fit.centroid[2], 7 + d[2], 1e-9);
    EXPECT_NEAR(fit.eigenvalues[0], 0, 1e-12);
}

TEST(PlaneFit, TooFewOrCollinearPointsHaveNoPlane) {
    EXPECT_FALSE(fitPlane(std::vector<Vec3d>{}).valid);
    EXPECT_TRUE(std::isnan(fitPlane(std::vector<Vec3d>{}).centroid[0]));
    const PlaneFit two = fitPlane(std::vector<Vec3d>{{0, 0, 0}, {2, 0, 0}});
    EXPECT_FALSE(two.valid);
    EXPECT_EQ(two.centroid, (Vec3d{1, 0, 0}));
    EXPECT_TRUE(std::isnan(two.orientation.dip));
    EXPECT_FALSE(fitPlane(std::vector<Vec3d>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}}).valid);
}

TEST(PlaneFit, InASectionModelTheFaultPlaneContainsTheThinAxis) {
    // A band dipping 45 degrees to the east in x-z, 6 units thick, in a slab 4 units thick in y
    // (the slab is thinner than the band: an unconstrained fit finds the slab's plane).
    std::vector<Vec3d> points;
    for (int u = 0; u < 60; ++u)           // down dip
        for (int w = -3; w <= 3; ++w)      // across the band
            for (int y = 0; y <= 4; ++y) { // through the slab
                const double s = u * 1.0, t = w * 1.0;
                points.push_back({s / std::sqrt(2.0) + t / std::sqrt(2.0), double(y),
                                  -s / std::sqrt(2.0) + t / std::sqrt(2.0)});
            }
    const PlaneFit free = fitPlane(points);
    EXPECT_NEAR(free.orientation.dip, 90.0, 1e-6); // the slab
    EXPECT_EQ(sectionAxis({100.0, 4.0, 50.0}), 1);
    EXPECT_EQ(sectionAxis({100.0, 40.0, 50.0}), -1);
    const PlaneFit fit = fitPlane(points, 1);
    ASSERT_TRUE(fit.valid);
    EXPECT_NEAR(fit.orientation.dip, 45.0, 1e-6);
    EXPECT_NEAR(fit.orientation.dipDirection, 90.0, 1e-6); // east
    EXPECT_NEAR(fit.normal[1], 0.0, 1e-12);
    EXPECT_LT(fit.eigenvalues[2], 1e3); // the real spreads, not the stand-in
    EXPECT_LE(fit.eigenvalues[0], fit.eigenvalues[1]);
}
