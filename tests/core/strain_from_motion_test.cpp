// Strain from motion (issue 36): exact values against hand-computed deformations of a jittered
// packing, the non-affine residual, periodic and triclinic boxes, 2-D data and missing ids.
#include "core/motion/strain_from_motion.hpp"

#include "core/model/frame_difference.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

using namespace faultline::core;

namespace {

using Vec = std::array<double, 3>;
using Map = std::function<Vec(const Vec&)>;

// A jittered simple-cubic packing of n^3 spheres (spacing 1, radius 0.5), ids 1..n^3.
Frame packing(int n, unsigned seed = 7, bool flatZ = false) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.15, 0.15);
    Frame f;
    std::int64_t id = 1;
    for (int k = 0; k < (flatZ ? 1 : n); ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                f.ids.push_back(id++);
                f.x.push_back(static_cast<float>(i + jitter(rng)));
                f.y.push_back(static_cast<float>(j + jitter(rng)));
                f.z.push_back(flatZ ? 0.0f : static_cast<float>(k + jitter(rng)));
            }
    f.radius.assign(f.ids.size(), 0.5f);
    f.finalize();
    return f;
}

// f in a known box from -0.5 to `hi` on each axis, periodic where asked.
Frame inBox(Frame f, const std::array<double, 3>& hi, const std::array<bool, 3>& periodic) {
    f.box.known = true;
    f.box.lo = {-0.5, -0.5, -0.5};
    f.box.hi = hi;
    f.box.periodic = periodic;
    f.finalize();
    return f;
}

// A jittered n^3 packing (spacing 1, ids 1..n^3) in the triclinic cell of edges a = (n,0,0),
// b = (xy,n,0), c = (xz,yz,n), periodic on every axis.
Frame triclinicPacking(int n, double xy, double xz, double yz, unsigned seed) {
    const double L = n;
    Frame f;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.12, 0.12);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                // Fractional (i, j, k) / n of the cell's edges.
                const double u = i + jitter(rng), v = j + jitter(rng), w = k + jitter(rng);
                f.ids.push_back(static_cast<std::int64_t>(f.ids.size()) + 1);
                f.x.push_back(static_cast<float>(u + v * xy / L + w * xz / L));
                f.y.push_back(static_cast<float>(v + w * yz / L));
                f.z.push_back(static_cast<float>(w));
            }
    f.radius.assign(f.ids.size(), 0.5f);
    f.box.known = true;
    f.box.triclinic = true;
    f.box.lo = {0, 0, 0};
    f.box.hi = {L, L, L};
    f.box.xy = xy;
    f.box.xz = xz;
    f.box.yz = yz;
    f.box.periodic = {true, true, true};
    f.finalize();
    return f;
}

// Row i of `f` moved by `by`, coming back through the opposite faces of triclinicPacking's cell
// (shifted by whole cell vectors) when it leaves.
void moveInCell(Frame& f, std::size_t i, const Vec& by) {
    const double L = f.box.hi[2] - f.box.lo[2], xy = f.box.xy, xz = f.box.xz, yz = f.box.yz;
    double p[3] = {f.x[i] + by[0], f.y[i] + by[1], f.z[i] + by[2]};
    const double nc = std::floor(p[2] / L);
    p[2] -= nc * L, p[1] -= nc * yz, p[0] -= nc * xz;
    const double nb = std::floor((p[1] - p[2] * yz / L) / L);
    p[1] -= nb * L, p[0] -= nb * xy;
    const double na = std::floor((p[0] - (p[1] - p[2] * yz / L) * xy / L - p[2] * xz / L) / L);
    p[0] -= na * L;
    f.x[i] = static_cast<float>(p[0]);
    f.y[i] = static_cast<float>(p[1]);
    f.z[i] = static_cast<float>(p[2]);
}

Frame mappedFrame(const Frame& ref, const Map& map) {
    Frame f;
    f.ids = ref.ids;
    f.radius = ref.radius;
    f.box = ref.box;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        const Vec p = map({ref.x[i], ref.y[i], ref.z[i]});
        f.x.push_back(static_cast<float>(p[0]));
        f.y.push_back(static_cast<float>(p[1]));
        f.z.push_back(static_cast<float>(p[2]));
    }
    f.finalize();
    return f;
}

// Affine map x -> F x + t (about the packing's centre).
Map affine(const double (&F)[3][3], Vec t = {0, 0, 0}) {
    std::array<std::array<double, 3>, 3> m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = F[i][j];
    return [m, t](const Vec& p) {
        Vec out;
        for (int i = 0; i < 3; ++i)
            out[i] = m[i][0] * (p[0] - 2) + m[i][1] * (p[1] - 2) + m[i][2] * (p[2] - 2) + 2 + t[i];
        return out;
    };
}

struct Expected {
    double shear, volumetric;
};

// E = (F^T F - I)/2 and its invariants, by hand in each test; here only the checks.
void expectEverywhere(const std::vector<AttributeColumn>& cols, Expected e, double tol = 2e-5) {
    ASSERT_EQ(cols.size(), 7u);
    EXPECT_EQ(cols[4].name, "ref_x");
    EXPECT_EQ(cols[6].name, "ref_z");
    EXPECT_EQ(cols[0].name, "shear_strain");
    EXPECT_EQ(cols[1].name, "volumetric_strain");
    EXPECT_EQ(cols[2].name, "d2min");
    EXPECT_EQ(cols[3].name, "displacement");
    for (std::size_t i = 0; i < cols[0].floats.size(); ++i) {
        ASSERT_NEAR(cols[0].floats[i], e.shear, tol) << "row " << i;
        ASSERT_NEAR(cols[1].floats[i], e.volumetric, tol) << "row " << i;
        ASSERT_NEAR(cols[2].floats[i], 0.0, 1e-4) << "row " << i; // affine: no residual
    }
}

} // namespace

TEST(StrainFromMotion, UniaxialStretch) {
    const Frame ref = packing(5);
    const double e = 0.1;
    const Frame now = mappedFrame(ref, affine({{1 + e, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
    const double exx = ((1 + e) * (1 + e) - 1) / 2; // 0.105
    // von Mises: sqrt(((Exx-0)^2 + 0 + (0-Exx)^2) / 6) = Exx / sqrt(3).
    expectEverywhere(strainFromMotion(now, ref, 1.5), {exx / std::sqrt(3.0), exx / 3});
}

// A cutoff whose square overflows a float takes every sphere as a neighbour (the padding of
// the last vector of neighbours must still not count).
TEST(StrainFromMotion, AHugeCutoffTakesEverySphere) {
    const Frame ref = packing(3); // 27 spheres: the last vector has 5 lanes of padding
    const double e = 0.1;
    const Frame now = mappedFrame(ref, affine({{1 + e, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
    const double exx = ((1 + e) * (1 + e) - 1) / 2;
    expectEverywhere(strainFromMotion(now, ref, 1e20), {exx / std::sqrt(3.0), exx / 3});
}

TEST(StrainFromMotion, SimpleShear) {
    const Frame ref = packing(5);
    const double g = 0.2;
    const Frame now = mappedFrame(ref, affine({{1, g, 0}, {0, 1, 0}, {0, 0, 1}}));
    // F^T F = [[1, g, 0], [g, 1 + g^2, 0], [0, 0, 1]]: Exy = g/2, Eyy = g^2/2.
    const double exy = g / 2, eyy = g * g / 2;
    const double shear = std::sqrt(exy * exy + (eyy * eyy + eyy * eyy) / 6);
    expectEverywhere(strainFromMotion(now, ref, 1.5), {shear, eyy / 3});
}

TEST(StrainFromMotion, RotationAndTranslationHaveNoStrain) {
    const Frame ref = packing(5);
    const double a = 0.7, c = std::cos(a), s = std::sin(a);
    const Frame now = mappedFrame(ref, affine({{c, -s, 0}, {s, c, 0}, {0, 0, 1}}, {3, -1, 0.5}));
    const auto cols = strainFromMotion(now, ref, 1.5);
    expectEverywhere(cols, {0, 0});
    // Displacement is each sphere's own.
    for (std::size_t i = 0; i < ref.size(); ++i) {
        const double d = std::hypot(now.x[i] - ref.x[i], now.y[i] - ref.y[i], now.z[i] - ref.z[i]);
        EXPECT_NEAR(cols[3].floats[i], d, 1e-5);
    }
}

TEST(StrainFromMotion, UniformDilation) {
    const Frame ref = packing(5);
    const double a = 0.05;
    const Frame now = mappedFrame(ref, affine({{1 + a, 0, 0}, {0, 1 + a, 0}, {0, 0, 1 + a}}));
    const double eii = ((1 + a) * (1 + a) - 1) / 2;
    expectEverywhere(strainFromMotion(now, ref, 1.5), {0, eii});
}

// One neighbour of the centre sphere moves off the affine field: d2min is the residual of the
// best-fit F, computed here by the normal equations of the centre's own neighbourhood.
TEST(StrainFromMotion, NonAffineResidualIsD2min) {
    const Frame ref = packing(5, 11);
    const std::size_t centre = 2 + 2 * 5 + 2 * 25; // lattice (2,2,2)
    const std::size_t moved = centre + 1;          // (3,2,2): a neighbour of the centre
    Frame now = ref;
    now.x[moved] += 0.12f;
    now.z[moved] -= 0.05f;
    now.finalize();
    const double cutoff = 1.5;
    const auto cols = strainFromMotion(now, ref, cutoff);

    double V[3][3] = {}, W[3][3] = {};
    std::vector<std::pair<Vec, Vec>> xy;
    for (std::size_t j = 0; j < ref.size(); ++j) {
        if (j == centre)
            continue;
        const Vec X = {double(ref.x[j]) - ref.x[centre], double(ref.y[j]) - ref.y[centre],
                       double(ref.z[j]) - ref.z[centre]};
        if (X[0] * X[0] + X[1] * X[1] + X[2] * X[2] > cutoff * cutoff)
            continue;
        const Vec Y = {double(now.x[j]) - now.x[centre], double(now.y[j]) - now.y[centre],
                       double(now.z[j]) - now.z[centre]};
        xy.push_back({X, Y});
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                V[a][b] += X[a] * X[b];
                W[a][b] += Y[a] * X[b];
            }
    }
    // F = W V^-1 by Gauss-Jordan on [V | I].
    double M[3][6];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 6; ++b)
            M[a][b] = b < 3 ? V[a][b] : (b - 3 == a ? 1.0 : 0.0);
    for (int p = 0; p < 3; ++p) {
        for (int r = 0; r < 3; ++r) {
            if (r == p)
                continue;
            const double f = M[r][p] / M[p][p];
            for (int b = 0; b < 6; ++b)
                M[r][b] -= f * M[p][b];
        }
    }
    double F[3][3] = {};
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            for (int k = 0; k < 3; ++k)
                F[a][b] += W[a][k] * M[k][3 + b] / M[k][k];
    double d2min = 0;
    for (const auto& [X, Y] : xy)
        for (int a = 0; a < 3; ++a) {
            const double r = Y[a] - (F[a][0] * X[0] + F[a][1] * X[1] + F[a][2] * X[2]);
            d2min += r * r;
        }
    EXPECT_GT(d2min, 1e-3);
    EXPECT_NEAR(cols[2].floats[centre], d2min, 1e-5 + 1e-4 * d2min);
    // Spheres far from the moved one keep no residual.
    EXPECT_NEAR(cols[2].floats[0], 0.0, 1e-6);
}

// A periodic box: a sphere near a face has neighbours across it, and one that crossed the face
// (wrapped back into the box) gets the strain it would have had unwrapped.
TEST(StrainFromMotion, PeriodicBoundariesUseTheMinimumImage) {
    const Frame ref = inBox(packing(6, 3), {5.5, 5.5, 5.5}, {true, true, false});
    // A translation by (0.8, -0.3, 0) and a small shear of z against x: wrapped back into the box.
    auto moveAndWrap = [&](bool wrap) {
        Frame now = ref;
        for (std::size_t i = 0; i < now.size(); ++i) {
            double x = now.x[i] + 0.8 + 0.02 * (now.z[i] - 2.5), y = now.y[i] - 0.3;
            if (wrap) {
                x -= 6.0 * std::floor((x + 0.5) / 6.0);
                y -= 6.0 * std::floor((y + 0.5) / 6.0);
            }
            now.x[i] = static_cast<float>(x);
            now.y[i] = static_cast<float>(y);
        }
        now.finalize();
        return now;
    };
    const Frame wrapped = moveAndWrap(true);
    const auto cols = strainFromMotion(wrapped, ref, 1.5);
    // Simple shear of x by z, g = 0.02, everywhere, edges included (their neighbours across
    // the periodic faces count).
    const double g = 0.02, exz = g / 2, ezz = g * g / 2;
    const double shear = std::sqrt(exz * exz + (ezz * ezz + ezz * ezz) / 6);
    std::size_t crossed = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        ASSERT_NEAR(cols[0].floats[i], shear, 2e-5) << "row " << i;
        ASSERT_NEAR(cols[2].floats[i], 0.0, 1e-4) << "row " << i;
        const double d = std::hypot(0.8 + 0.02 * (ref.z[i] - 2.5), 0.3);
        ASSERT_NEAR(cols[3].floats[i], d, 1e-5) << "row " << i;
        crossed += std::fabs(wrapped.x[i] - ref.x[i]) > 3 ? 1 : 0;
    }
    EXPECT_GT(crossed, 20u);
}

// A sphere that crossed a face of a long periodic box (6000 along x) and came back in at the far
// end gets the strain it has unwrapped: its motion is worked out in double before it is stored as
// a float (in float, its position there minus its reference lost up to 2.4e-4).
TEST(StrainFromMotion, CrossingTheFaceOfALongPeriodicBoxKeepsThePrecision) {
    const Frame ref = inBox(packing(6, 3), {5999.5, 5.5, 5.5}, {true, false, false});
    // The same positions twice: wrapped in at the far end, and where they are unwrapped.
    Frame open = ref, wrapped = ref;
    std::size_t crossed = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        const double x = ref.x[i] - 0.8 + 0.02 * (ref.z[i] - 2.5);
        if (x < -0.5) {
            wrapped.x[i] = static_cast<float>(x + 6000.0);
            open.x[i] = static_cast<float>(double(wrapped.x[i]) - 6000.0); // exact
            ++crossed;
        } else {
            wrapped.x[i] = open.x[i] = static_cast<float>(x);
        }
    }
    open.finalize();
    wrapped.finalize();
    ASSERT_GT(crossed, 20u);
    const auto a = strainFromMotion(open, ref, 1.5), b = strainFromMotion(wrapped, ref, 1.5);
    for (std::size_t i = 0; i < ref.size(); ++i)
        for (int c : {0, 1, 2, 3})
            ASSERT_NEAR(b[std::size_t(c)].floats[i], a[std::size_t(c)].floats[i], 1e-6)
                << "column " << c << ", row " << i;
}

// A triclinic periodic cell (LAMMPS' tilt factors): spheres wrapped into it by the cell vectors.
TEST(StrainFromMotion, TriclinicCellsWrapAlongTheirEdges) {
    const Frame ref = triclinicPacking(6, 1.5, -1.0, 0.75, 5);
    // Every sphere moves by (0.4, 0.9, -0.7); those leaving the cell come back through the
    // opposite face, shifted by whole cell vectors.
    Frame now = ref;
    for (std::size_t i = 0; i < now.size(); ++i)
        moveInCell(now, i, {0.4, 0.9, -0.7});
    now.finalize();
    const auto cols = strainFromMotion(now, ref, 1.5);
    const double moved = std::sqrt(0.4 * 0.4 + 0.9 * 0.9 + 0.7 * 0.7);
    for (std::size_t i = 0; i < ref.size(); ++i) {
        ASSERT_NEAR(cols[0].floats[i], 0.0, 3e-5) << "row " << i;
        ASSERT_NEAR(cols[2].floats[i], 0.0, 1e-4) << "row " << i;
        ASSERT_NEAR(cols[3].floats[i], moved, 1e-5) << "row " << i;
    }
}

// 2-D data: every centre at z = 0; the in-plane 2 x 2 form (as OVITO's 2-D mode).
TEST(StrainFromMotion, TwoDimensionalDataUsesThePlaneForm) {
    const Frame ref = packing(7, 13, /*flatZ=*/true);
    const double g = 0.1;
    const Frame now = mappedFrame(ref, affine({{1, g, 0}, {0, 1, 0}, {0, 0, 1}}));
    const auto cols = strainFromMotion(now, ref, 1.8); // corners keep 3 neighbours
    // E = [[0, g/2], [g/2, g^2/2]]: shear = sqrt(Exy^2 + (Exx-Eyy)^2 / 2), vol = (Exx+Eyy)/2.
    const double exy = g / 2, eyy = g * g / 2;
    expectEverywhere(cols, {std::sqrt(exy * exy + eyy * eyy / 2), eyy / 2});
}

// Rows in another order, a sphere gone from the reference (NaN), one gone from the current
// frame (its neighbours do without it), too few neighbours (NaN).
TEST(StrainFromMotion, SpheresAreMatchedById) {
    const Frame ref = packing(5);
    const double e = 0.1;
    Frame stretched = mappedFrame(ref, affine({{1 + e, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
    Frame now;
    for (std::size_t k = stretched.size(); k-- > 1;) { // reversed; id 1 (row 0) is gone
        now.ids.push_back(stretched.ids[k]);
        now.x.push_back(stretched.x[k]);
        now.y.push_back(stretched.y[k]);
        now.z.push_back(stretched.z[k]);
    }
    now.ids.push_back(1000); // new: not in the reference
    now.x.push_back(2);
    now.y.push_back(2);
    now.z.push_back(2);
    now.radius.assign(now.ids.size(), 0.5f);
    now.finalize();
    const auto cols = strainFromMotion(now, ref, 1.5);
    const double exx = ((1 + e) * (1 + e) - 1) / 2;
    for (std::size_t i = 0; i + 1 < now.size(); ++i) {
        ASSERT_NEAR(cols[0].floats[i], exx / std::sqrt(3.0), 2e-5) << "id " << now.ids[i];
        ASSERT_NEAR(cols[1].floats[i], exx / 3, 2e-5);
    }
    for (const auto& c : cols)
        EXPECT_TRUE(std::isnan(c.floats.back())) << c.name;

    // Three spheres far apart: no neighbours within the cutoff.
    Frame sparse;
    sparse.ids = {1, 2, 3};
    sparse.x = {0, 10, 20};
    sparse.y = {0, 0, 5};
    sparse.z = {0, 3, 0};
    sparse.radius = {0.5f, 0.5f, 0.5f};
    sparse.finalize();
    const auto none = strainFromMotion(sparse, sparse, 1.5);
    EXPECT_TRUE(std::isnan(none[0].floats[0]));
    EXPECT_EQ(none[3].floats[0], 0.0f); // it did not move
}

// A centre that is not a finite number now (a corrupt row; any axis) is a sphere without a value,
// as one gone: every column NaN on its row, and its neighbours summed without it.
TEST(StrainFromMotion, ACentreThatIsNoNumberHasNoValue) {
    const Frame ref = packing(5);
    const double e = 0.1;
    Frame now = mappedFrame(ref, affine({{1 + e, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
    // Inside the packing: x NaN, z NaN, y infinite.
    const std::size_t bad[3] = {62, 31, 87};
    now.x[bad[0]] = std::numeric_limits<float>::quiet_NaN();
    now.z[bad[1]] = std::numeric_limits<float>::quiet_NaN();
    now.y[bad[2]] = std::numeric_limits<float>::infinity();
    now.finalize();
    const auto cols = strainFromMotion(now, ref, 1.5);
    const double exx = ((1 + e) * (1 + e) - 1) / 2;
    for (std::size_t i = 0; i < now.size(); ++i) {
        if (i == bad[0] || i == bad[1] || i == bad[2])
            continue;
        ASSERT_NEAR(cols[0].floats[i], exx / std::sqrt(3.0), 2e-5) << "row " << i;
        ASSERT_NEAR(cols[2].floats[i], 0.0, 1e-4) << "row " << i;
        ASSERT_TRUE(std::isfinite(cols[3].floats[i])) << "row " << i;
    }
    for (std::size_t b : bad)
        for (const auto& c : cols)
            EXPECT_TRUE(std::isnan(c.floats[b])) << c.name << " row " << b;
}

TEST(StrainFromMotion, DefaultCutoffIsOneAndAHalfMedianDiameters) {
    Frame f = packing(4);
    for (std::size_t i = 0; i < f.size(); ++i)
        f.radius[i] = i % 3 == 0 ? 0.6f : 0.4f; // median 0.4
    EXPECT_DOUBLE_EQ(defaultStrainCutoff(f), 1.5 * 0.8f);
    // Prefixes name the columns.
    const auto cols = strainFromMotion(f, f, 0, "inc_");
    EXPECT_EQ(cols[0].name, "inc_shear_strain");
    EXPECT_EQ(cols[3].name, "inc_displacement");
    // No radii: from the spacing of a close packing in the centres' bounds.
    f.radiusIsDefault = true;
    double volume = 1;
    for (int a = 0; a < 3; ++a)
        volume *= double(f.centreMax()[a]) - f.centreMin()[a];
    EXPECT_NEAR(defaultStrainCutoff(f), 1.5 * std::cbrt(0.64 * volume * 6 / (M_PI * 64)), 1e-9);
}

// How many spheres lie within a cutoff, from the density of the centres in their bounds: about
// 4/3 pi c^3 in a lattice of spacing 1, pi c^2 in a 2-D one, never more than all the others.
TEST(StrainFromMotion, NeighboursWithinACutoffFromTheDensity) {
    auto extent = [](const Frame& f, int a) {
        return double(f.centreMax()[a]) - double(f.centreMin()[a]);
    };
    const Frame f = packing(20);
    const double volume = extent(f, 0) * extent(f, 1) * extent(f, 2);
    EXPECT_NEAR(strainNeighboursWithin(f, 2.0), 8000.0 / volume * 4.0 / 3.0 * M_PI * 8.0, 1e-9);
    EXPECT_EQ(strainNeighboursWithin(f, 1e6), 7999.0);
    EXPECT_NEAR(packingStrainCutoff(f), 1.5 * std::cbrt(0.64 * volume * 6 / (M_PI * 8000)), 1e-9);
    const Frame flat = packing(30, 7, true);
    EXPECT_NEAR(strainNeighboursWithin(flat, 2.0),
                900.0 / (extent(flat, 0) * extent(flat, 1)) * M_PI * 4.0, 1e-9);
    Frame two;
    two.ids = {1, 2};
    two.x = {0, 0}, two.y = {0, 0}, two.z = {0, 0}, two.radius = {0.5f, 0.5f};
    two.finalize();
    EXPECT_EQ(strainNeighboursWithin(two, 1.0), 1.0); // every centre at one point: all of them
    two.ids.pop_back(), two.x.pop_back(), two.y.pop_back(), two.z.pop_back();
    two.radius.pop_back();
    two.finalize();
    EXPECT_EQ(strainNeighboursWithin(two, 1.0), 0.0); // no other sphere
}

// The AVX2 neighbour sums (used where the CPU has them) and the baseline ones give the same
// values, up to float rounding, on a non-affine motion of about half a cell along every edge of a
// triclinic cell periodic on all three axes (neighbours' motions straddle half a cell, so both
// wrap U on every axis with every tilt), with a sphere gone and a centre that is no number.
TEST(StrainFromMotion, TheAvx2AndBaselineSumsAgree) {
    detail::setStrainBaselineOnly(false);
    if (!detail::strainUsesAvx2())
        GTEST_SKIP() << "no AVX2 and FMA on this CPU: only the baseline sums run";
    const Frame ref = triclinicPacking(9, 1.5, -1.0, 0.75, 23);
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> noise(-0.08, 0.08);
    Frame now = ref;
    for (std::size_t i = 0; i < now.size(); ++i) // a shear and about half a cell along each axis
        moveInCell(now, i,
                   {4.4 + 0.05 * now.z[i] + noise(rng), 4.45 + noise(rng), 4.5 + noise(rng)});
    now.ids[100] = 100000; // gone from the reference's point of view
    now.y[200] = std::numeric_limits<float>::quiet_NaN();
    now.finalize();
    detail::setStrainBaselineOnly(true);
    const auto baseline = strainFromMotion(now, ref, 1.6);
    detail::setStrainBaselineOnly(false);
    const auto fast = strainFromMotion(now, ref, 1.6);
    ASSERT_EQ(baseline.size(), fast.size());
    int finite = 0;
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < now.size(); ++i) {
            const float a = baseline[c].floats[i], b = fast[c].floats[i];
            ASSERT_EQ(std::isnan(a), std::isnan(b)) << baseline[c].name << " row " << i;
            if (std::isnan(a))
                continue;
            ++finite;
            ASSERT_NEAR(a, b, 1e-6 + 1e-4 * std::fabs(a)) << baseline[c].name << " row " << i;
        }
    EXPECT_GT(finite, 3 * 700);
    // Each column's range, kept as the columns are filled, is the one a scan of it gives.
    for (const auto* cols : {&baseline, &fast})
        for (const AttributeColumn& c : *cols) {
            AttributeColumn scanned = c;
            cacheColumnRange(scanned);
            EXPECT_EQ(c.min, scanned.min) << c.name;
            EXPECT_EQ(c.max, scanned.max) << c.name;
            EXPECT_LT(c.min, c.max) << c.name;
        }
    EXPECT_TRUE(std::isnan(fast[0].floats[100]));
    EXPECT_TRUE(std::isnan(fast[0].floats[200]));
    // And both right: a simple shear of 0.05 gives about 0.025 (the noise adds a little); a
    // neighbour's motion left a cell edge off would give strains of order 1.
    for (std::size_t i = 0; i < now.size(); ++i)
        if (i != 100 && i != 200) {
            ASSERT_LT(fast[0].floats[i], 0.2f) << "row " << i;
        }
}

// The AVX-512 sums (used where the CPU has them) give the AVX2 ones' values to the last bit, every
// column: on the triclinic cell periodic on all three axes with motions that straddle half a cell
// (both wrap U on every axis), on a sheared block with no wrap, and on 2-D data.
TEST(StrainFromMotion, TheAvx512AndAvx2SumsAgreeToTheBit) {
    detail::setStrainBaselineOnly(false);
    detail::setStrainAvx512Allowed(true);
    if (!detail::strainUsesAvx512())
        GTEST_SKIP() << "no AVX-512 on this CPU: the AVX2 sums run";
    std::vector<std::pair<Frame, Frame>> cases; // (now, reference)
    {
        const Frame ref = triclinicPacking(9, 1.5, -1.0, 0.75, 23);
        std::mt19937 rng(31);
        std::uniform_real_distribution<double> noise(-0.08, 0.08);
        Frame now = ref;
        for (std::size_t i = 0; i < now.size(); ++i)
            moveInCell(now, i,
                       {4.4 + 0.05 * now.z[i] + noise(rng), 4.45 + noise(rng), 4.5 + noise(rng)});
        now.ids[100] = 100000; // gone
        now.y[200] = std::numeric_limits<float>::quiet_NaN();
        now.finalize();
        cases.emplace_back(now, ref);
    }
    for (const bool flat : {false, true}) {
        const Frame ref = packing(flat ? 40 : 16, 5, flat);
        std::mt19937 rng(37);
        std::uniform_real_distribution<double> noise(-0.03, 0.03);
        Frame now = ref;
        for (std::size_t i = 0; i < now.size(); ++i) {
            now.x[i] += static_cast<float>(0.06 * now.y[i] + noise(rng));
            now.y[i] += static_cast<float>(noise(rng));
        }
        now.finalize();
        cases.emplace_back(now, ref);
    }
    for (const auto& [now, ref] : cases) {
        detail::setStrainAvx512Allowed(false);
        const auto avx2 = strainFromMotion(now, ref, 0);
        detail::setStrainAvx512Allowed(true);
        const auto avx512 = strainFromMotion(now, ref, 0);
        ASSERT_EQ(avx2.size(), avx512.size());
        std::size_t finite = 0;
        for (std::size_t c = 0; c < avx2.size(); ++c) {
            ASSERT_EQ(avx2[c].floats.size(), avx512[c].floats.size());
            EXPECT_EQ(std::memcmp(avx2[c].floats.data(), avx512[c].floats.data(),
                                  avx2[c].floats.size() * sizeof(float)),
                      0)
                << avx2[c].name << ", " << now.size() << " spheres";
            for (float v : avx512[c].floats)
                finite += std::isfinite(v) ? 1 : 0;
        }
        EXPECT_GT(finite, 6 * now.size());
    }
}

// Hostile centres and boxes (a reader's checks let finite extremes through): huge and tiny
// coordinates, a periodic box far smaller than the spacing, ids in the current frame that the
// reference lacks. No kind of sums (baseline, AVX2, AVX-512 where the CPU has it) reads out of
// bounds (the sanitizer builds run this) and all give NaN for exactly the same spheres.
TEST(StrainFromMotion, HostileCentresAndBoxesDoNotBreakEitherSums) {
    std::mt19937 rng(77);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int round = 0; round < 12; ++round) {
        Frame ref = packing(6, 100 + round);
        ref.box.known = round % 3 != 0;
        ref.box.lo = {-0.5, -0.5, -0.5};
        const double l = round % 4 == 1 ? 1e-20 : round % 4 == 2 ? 1e20 : 6.0;
        ref.box.hi = {ref.box.lo[0] + l, ref.box.lo[1] + l, ref.box.lo[2] + l};
        ref.box.triclinic = round % 2 == 0;
        ref.box.xy = 0.3 * l;
        ref.box.periodic = {round % 2 == 0, true, round % 5 == 0};
        Frame now = ref;
        for (std::size_t i = 0; i < now.size(); ++i) {
            now.x[i] += static_cast<float>(0.05 * u(rng));
            if (i % 17 == std::size_t(round) % 17)
                now.y[i] = static_cast<float>(1e30 * u(rng));
            if (i % 23 == std::size_t(round) % 23)
                now.z[i] = 1e-40f;
            if (i % 29 == 0)
                now.ids[i] += 100000; // not in the reference
        }
        ref.x[std::size_t(round)] = 3e38f;
        ref.finalize();
        now.finalize();
        for (const double cutoff : {1.5, 1e-30, 1e30}) {
            detail::setStrainBaselineOnly(true);
            const auto baseline = strainFromMotion(now, ref, cutoff);
            detail::setStrainBaselineOnly(false);
            const auto fast = strainFromMotion(now, ref, cutoff);
            detail::setStrainAvx512Allowed(false); // the AVX2 sums where AVX-512 ran above
            const auto avx2 = strainFromMotion(now, ref, cutoff);
            detail::setStrainAvx512Allowed(true);
            ASSERT_EQ(baseline.size(), fast.size());
            for (std::size_t i = 0; i < now.size(); ++i) {
                ASSERT_EQ(std::isnan(baseline[0].floats[i]), std::isnan(fast[0].floats[i]))
                    << "round " << round << " cutoff " << cutoff << " row " << i;
                ASSERT_EQ(std::isnan(avx2[0].floats[i]), std::isnan(fast[0].floats[i]))
                    << "round " << round << " cutoff " << cutoff << " row " << i;
            }
        }
    }
    // No centre of the reference is a number: every value NaN.
    Frame ref = packing(3);
    for (std::size_t i = 0; i < ref.size(); ++i)
        ref.x[i] = std::numeric_limits<float>::quiet_NaN();
    ref.finalize();
    const Frame now = packing(3);
    for (const auto& c : strainFromMotion(now, ref, 0))
        for (float v : c.floats)
            ASSERT_TRUE(std::isnan(v)) << c.name;
}

// The values do not depend on how many threads compute them (the cells are split among them
// differently, and the spheres solved four at a time or one by one accordingly): bit for bit,
// with the AVX2 sums and with the baseline ones, on a sheared packing periodic along y with a
// sphere gone.
TEST(StrainFromMotion, ValuesDoNotDependOnTheThreadCount) {
    const Frame ref = inBox(packing(28, 41), {27.5, 27.5, 27.5}, {false, true, false});
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> noise(-0.03, 0.03);
    Frame now = ref;
    for (std::size_t i = 0; i < now.size(); ++i) {
        now.x[i] += static_cast<float>(0.04 * now.z[i] + noise(rng));
        now.y[i] += static_cast<float>(noise(rng));
    }
    now.ids[500] = 10000000; // gone
    now.finalize();
    for (const bool baseline : {false, true}) {
        detail::setStrainBaselineOnly(baseline);
        std::vector<AttributeColumn> one;
        {
            tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
            one = strainFromMotion(now, ref, 0);
        }
        const auto all = strainFromMotion(now, ref, 0);
        ASSERT_EQ(one.size(), all.size());
        for (std::size_t c = 0; c < one.size(); ++c) {
            ASSERT_EQ(one[c].floats.size(), all[c].floats.size());
            EXPECT_EQ(std::memcmp(one[c].floats.data(), all[c].floats.data(),
                                  one[c].floats.size() * sizeof(float)),
                      0)
                << one[c].name << (baseline ? " (baseline)" : "");
        }
        EXPECT_TRUE(std::isnan(all[0].floats[500]));
    }
    detail::setStrainBaselineOnly(false);
}
