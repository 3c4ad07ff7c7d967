// core/model/packing: the spacing of a close packing of a frame's spheres, and radii far larger
// than it (another unit than the centres) found and scaled down for drawing.
#include "core/model/packing.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace faultline::core;

namespace {

Frame lattice(int nx, int ny, int nz, float radius) {
    Frame f;
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                f.ids.push_back(std::int64_t(f.ids.size()) + 1);
                f.x.push_back(float(x));
                f.y.push_back(float(y));
                f.z.push_back(float(z));
            }
    f.radius.assign(f.ids.size(), radius);
    f.finalize();
    return f;
}

} // namespace

TEST(Packing, SpacingFromTheCentresBounds) {
    const Frame f = lattice(20, 20, 20, 0.5f);
    EXPECT_NEAR(packingSpacing(f), std::cbrt(0.64 * 19 * 19 * 19 * 6 / (M_PI * 8000)), 1e-12);
    EXPECT_EQ(flatAxis(f), -1);
    const Frame flat = lattice(30, 30, 1, 0.5f); // 2-D: the area, and a close packing of discs
    EXPECT_EQ(flatAxis(flat), 2);
    EXPECT_NEAR(packingSpacing(flat), std::sqrt(0.84 * 29 * 29 * 4 / (M_PI * 900)), 1e-12);
    EXPECT_EQ(packingSpacing(lattice(1, 1, 1, 0.5f)), 1.0); // no bounds: undefined
}

TEST(Packing, RadiiFarLargerThanTheSpacingAreDrawnScaledDown) {
    // A packing: the median diameter about the spacing, drawn as it is.
    const Frame packed = lattice(14, 14, 14, 0.5f);
    EXPECT_EQ(medianRadius(packed), 0.5);
    EXPECT_NEAR(radiiOverSpacing(packed), 1.0 / packingSpacing(packed), 1e-12);
    EXPECT_LT(radiiOverSpacing(packed), 1.1);
    EXPECT_EQ(radiusDrawScale(packed), 1.0);
    // Radii 40 times too large (millimetres beside centimetres, say): drawn one spacing wide.
    Frame mm = lattice(14, 14, 14, 20.0f);
    const double ratio = radiiOverSpacing(mm);
    EXPECT_NEAR(ratio, 40.0 / packingSpacing(mm), 1e-9);
    EXPECT_NEAR(radiusDrawScale(mm), 1.0 / ratio, 1e-12);
    EXPECT_NEAR(20.0 * radiusDrawScale(mm) * 2.0, packingSpacing(mm), 1e-9);
    EXPECT_EQ(radiiUnitNote(mm), "the median diameter is 40, about 40 times the spacing of the "
                                 "centres (0.9928): are the radii in another unit?");
    // Radii a thousandth of the spacing: far below, drawn as they are (dilute flows exist).
    const Frame m = lattice(14, 14, 14, 0.0005f);
    EXPECT_LT(radiiOverSpacing(m), kRadiiTinyOverSpacing);
    EXPECT_EQ(radiusDrawScale(m), 1.0);
    EXPECT_EQ(radiiUnitNote(m), "the median diameter is 0.001, about 1/993 of the spacing of "
                                "the centres (0.9928): are the radii in another unit?");
    EXPECT_EQ(radiiUnitNote(packed), "");
    // Just above the spacing (overlapping grains, an SPH smoothing length): drawn as they are.
    EXPECT_EQ(radiusDrawScale(lattice(14, 14, 14, 1.5f)), 1.0);
    // No radius column, or none positive: nothing to compare.
    mm.radiusIsDefault = true;
    EXPECT_TRUE(std::isnan(radiiOverSpacing(mm)));
    EXPECT_EQ(radiusDrawScale(mm), 1.0);
    EXPECT_TRUE(std::isnan(medianRadius(lattice(4, 4, 4, 0.0f))));
    EXPECT_EQ(radiusDrawScale(lattice(4, 4, 4, 0.0f)), 1.0);
    // A few spheres fill no bounds: two side by side are no packing to compare with.
    EXPECT_TRUE(std::isnan(radiiOverSpacing(lattice(2, 1, 1, 1.0f))));
    EXPECT_TRUE(std::isnan(radiiOverSpacing(lattice(3, 3, 7, 20.0f)))); // 63 spheres
    EXPECT_FALSE(std::isnan(radiiOverSpacing(lattice(4, 4, 4, 20.0f))));
    EXPECT_EQ(radiusDrawScale(lattice(1, 1, 1, 20.0f)), 1.0);
}
