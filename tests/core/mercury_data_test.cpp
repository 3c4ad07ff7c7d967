// MercuryDPM .data (3-D and 2-D time steps, its documented xballs layout): exact values, and
// malformed, truncated or corrupted text as InputError naming the line.
#include "core/data/dataset.hpp"
#include "core/io/frame_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/mercury_data.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace faultline::core;

namespace {

std::string mercuryErrorOf(const std::string& text) {
    try {
        parseMercuryDataFrame("m.data", text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(MercuryData, ThreeDimensionalStepsReadExactly) {
    const std::string path = faultline::test::dataFile("mercurydpm_layout_3d_2steps.data");
    EXPECT_EQ(detectFormat(path), FileFormat::MercuryData);
    auto ds = Dataset::open({path});
    ASSERT_EQ(ds->frameCount(), 2u);
    EXPECT_EQ(ds->location(1).time, 0.2);
    const auto f = ds->frame(1);
    ASSERT_EQ(f->size(), 8u);
    EXPECT_TRUE(f->idsAreRowNumbers);
    EXPECT_FALSE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(),
              (std::vector<std::string>{"vx", "vy", "vz", "orientation_x", "orientation_y",
                                        "orientation_z", "angular_velocity_x", "angular_velocity_y",
                                        "angular_velocity_z", "species"}));
    // Row 3: i=0 j=1 k=1 at time 0.2: z = 1.5 - 0.0002, vz = -0.0002, gamma = 0.1, species 0.
    EXPECT_EQ(f->x[3], 0.5f);
    EXPECT_EQ(f->y[3], 1.5f);
    EXPECT_EQ(f->z[3], float(1.5 - 0.0002));
    EXPECT_EQ(f->radius[3], 0.5f);
    EXPECT_EQ(f->attribute("vz")->floats[3], -0.0002f);
    EXPECT_EQ(f->attribute("orientation_z")->floats[3], 0.1f);
    EXPECT_EQ(f->attribute("species")->ints[3], 0);
    EXPECT_EQ(f->attribute("species")->ints[1], 1);
    EXPECT_EQ(f->attribute("angular_velocity_y")->floats[7], 0.01f);
    EXPECT_TRUE(f->box.known);
    EXPECT_EQ(f->box.hi, (std::array<double, 3>{2, 2, 2}));
}

TEST(MercuryData, TwoDimensionalStepsLieInTheXyPlane) {
    auto ds = Dataset::open({faultline::test::dataFile("mercurydpm_layout_2d_2steps.data")});
    ASSERT_EQ(ds->frameCount(), 2u);
    const auto f = ds->frame(1);
    ASSERT_EQ(f->size(), 5u);
    EXPECT_EQ(f->attributeNames(),
              (std::vector<std::string>{"vx", "vy", "orientation", "angular_velocity", "species"}));
    EXPECT_EQ(f->x[4], float(0.1 + 0.2 * 4 + 0.001));
    EXPECT_EQ(f->y[4], 0.5f);
    EXPECT_EQ(f->z[4], 0.0f);
    EXPECT_EQ(f->radius[4], float(0.02 + 0.005 * 4));
    EXPECT_EQ(f->attribute("vy")->floats[2], -0.1f);
    EXPECT_EQ(f->attribute("species")->ints[3], 1);
}

TEST(MercuryData, MalformedStepsNameLineAndWhat) {
    const std::string h = "1 0 0 0 0 1 1 1\n";
    EXPECT_EQ(mercuryErrorOf("1 0 0 0 0 1 1\n"),
              "m.data:1: expected a time step header of 8 numbers (N time xmin ymin zmin xmax "
              "ymax zmax) or 6 in 2-D, found 7 values");
    EXPECT_EQ(mercuryErrorOf("x 0 0 0 0 1 1 1\n"),
              "m.data:1: expected the number of particles first, found 'x'");
    EXPECT_EQ(mercuryErrorOf("1 0 0 0 nan 1 1 1\n"),
              "m.data:1: header value 5: expected a finite number, found 'nan'");
    EXPECT_EQ(mercuryErrorOf(h + "0 0 0 0 0 0 0.5 0 0 0 0 0 0\n"),
              "m.data:2: expected 14 values (a 3-D MercuryDPM row), found 13");
    EXPECT_EQ(mercuryErrorOf(h + "0 0 0 0 0 0 -1 0 0 0 0 0 0 0\n"),
              "m.data:2: the radius must be positive, found '-1'");
    EXPECT_EQ(mercuryErrorOf(h + "0 0 0 0 0 0 0.5 0 0 0 0 0 0 0.5\n"),
              "m.data:2: the species index must be a whole number, found '0.5'");
    EXPECT_EQ(mercuryErrorOf(h + "0 0 0 0 0 0 0.5 0 0 0 0 0 0 inf\n"),
              "m.data:2: value 14: expected a finite number, found 'inf'");
    EXPECT_EQ(mercuryErrorOf("2 0 0 0 0 1 1 1\n0 0 0 0 0 0 0.5 0 0 0 0 0 0 0\n"),
              "m.data:3: file ends after 1 of 2 particle rows");
    EXPECT_NE(mercuryErrorOf("99999999999 0 0 0 0 1 1 1\n0 0\n").find("announces"),
              std::string::npos);
}

TEST(MercuryData, TruncatedFileNamesTheStep) {
    faultline::test::TempDir dir;
    std::ifstream in(faultline::test::dataFile("mercurydpm_layout_3d_2steps.data"));
    const std::string good((std::istreambuf_iterator<char>(in)), {});
    const std::string p = dir.write("cut.data", good.substr(0, good.size() - 60));
    try {
        indexDataFile(p);
        FAIL() << "accepted a truncated file";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("particle rows of time step 1"), std::string::npos)
            << e.what();
    }
    // Opened: the complete step reads, and a note names the one left out.
    auto ds = Dataset::open({p});
    EXPECT_EQ(ds->frameCount(), 1u);
    ASSERT_EQ(ds->notes().size(), 1u);
    EXPECT_NE(ds->notes()[0].find("particle rows of time step 1"), std::string::npos)
        << ds->notes()[0];
}

TEST(MercuryData, CorruptedBytesOnlyEverGiveInputErrors) {
    std::ifstream in(faultline::test::dataFile("mercurydpm_layout_3d_2steps.data"));
    const std::string good((std::istreambuf_iterator<char>(in)), {});
    for (std::size_t n = 0; n < good.size(); n += 3)
        try {
            parseMercuryDataFrame("m.data", good.substr(0, n));
        } catch (const InputError&) {
        }
    for (std::size_t i = 0; i < good.size(); ++i)
        for (char c : {'\0', '\n', ' ', '-', '9', 'e'}) {
            std::string bad = good;
            bad[i] = c;
            try {
                parseMercuryDataFrame("m.data", bad);
            } catch (const InputError&) {
            }
        }
}
