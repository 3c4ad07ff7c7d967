// XYZ and extended XYZ: files written by ASE 3.22 (tests/data/scripts/ase322_extxyz.py) read to
// exact values; malformed and hostile text gives InputError naming the line.
#include "core/data/dataset.hpp"
#include "core/io/extxyz.hpp"
#include "core/io/frame_source.hpp"
#include "core/io/input_error.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace faultline::core;

namespace {

std::string errorOf(const std::string& text) {
    try {
        parseXyzFrame("t.xyz", text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

const AttributeColumn& column(const Frame& f, const char* name) {
    const AttributeColumn* c = f.attribute(name);
    if (!c)
        throw std::runtime_error(std::string("no column ") + name);
    return *c;
}

} // namespace

TEST(ExtXyz, AseFramesReadWithEveryPropertyAndTheCell) {
    const std::string path = faultline::test::dataFile("ase322_extxyz_3frames.xyz");
    EXPECT_EQ(detectFormat(path), FileFormat::Xyz);
    auto ds = Dataset::open({path});
    ASSERT_EQ(ds->frameCount(), 3u);
    EXPECT_EQ(ds->location(2).timestep, 2000);
    for (std::size_t t = 0; t < 3; ++t) {
        SCOPED_TRACE(t);
        const auto f = ds->frame(t);
        ASSERT_EQ(f->size(), 6u);
        EXPECT_EQ(f->timestep, std::int64_t(1000 * t));
        EXPECT_FALSE(f->idsAreRowNumbers);
        EXPECT_FALSE(f->radiusIsDefault);
        EXPECT_EQ(f->attributeNames(),
                  (std::vector<std::string>{"species", "strain", "broken", "momenta_x", "momenta_y",
                                            "momenta_z"}));
        const AttributeColumn& species = column(*f, "species");
        const AttributeColumn& broken = column(*f, "broken");
        EXPECT_TRUE(species.isInteger());
        for (std::size_t i = 0; i < 6; ++i) {
            EXPECT_EQ(f->ids[i], std::int64_t(100 + i));
            EXPECT_EQ(f->x[i], float(1.0 * double(i)));
            EXPECT_EQ(f->y[i], float(0.5 * double(i % 2)));
            EXPECT_EQ(f->z[i], float(0.25 * double(t)));
            EXPECT_EQ(f->radius[i], float(0.5 + 0.125 * double(i)));
            EXPECT_EQ(column(*f, "strain").floats[i], float(0.01 * double(i) * double(t + 1)));
            EXPECT_EQ(broken.ints[i], (i % 2 == 0 && t > 0) ? 1 : 0);
            // Si O Si O O Si: codes in order of first appearance.
            EXPECT_EQ(species.ints[i], (i == 0 || i == 2 || i == 5) ? 1 : 2);
        }
        EXPECT_TRUE(f->box.known);
        EXPECT_EQ(f->box.hi, (std::array<double, 3>{10.0, 5.0, 4.0}));
        EXPECT_EQ(f->box.periodic, (std::array<bool, 3>{true, true, false}));
    }
}

TEST(ExtXyz, PlainXyzIsSpeciesAndPositions) {
    auto ds = Dataset::open({faultline::test::dataFile("ase322_plain.xyz")});
    ASSERT_EQ(ds->frameCount(), 1u);
    const auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 6u);
    EXPECT_TRUE(f->idsAreRowNumbers);
    EXPECT_TRUE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(), (std::vector<std::string>{"species"}));
    EXPECT_EQ(f->x[5], 5.0f);
    EXPECT_EQ(f->y[5], 0.5f);
}

TEST(ExtXyz, MalformedFramesNameLineAndWhat) {
    const std::string props = "Properties=species:S:1:pos:R:3:radius:R:1\n";
    EXPECT_EQ(errorOf("two\nc\n"), "t.xyz:1: expected the number of particles, found 'two'");
    EXPECT_EQ(errorOf("1\n" + props + "Si 0 0\n"),
              "t.xyz:3: expected 5 values (as Properties= says), found 3");
    EXPECT_EQ(errorOf("1\n" + props + "Si 0 nan 0 1\n"),
              "t.xyz:3: column 3 ('pos'): expected a finite number, found 'nan'");
    EXPECT_EQ(errorOf("1\n" + props + "Si 0 0 0 -1\n"),
              "t.xyz:3: column 'radius' must be positive, found '-1'");
    EXPECT_EQ(errorOf("2\n" + props + "Si 0 0 0 1\n"),
              "t.xyz:4: file ends after 1 of 2 particle rows");
    EXPECT_NE(errorOf("1\nProperties=species:S:1:pos:R:2\nSi 0 0\n").find("no positions"),
              std::string::npos);
    EXPECT_NE(
        errorOf("1\nProperties=species:S:1:pos:Q:3\nSi 0 0 0\n").find("expected R, I, L or S"),
        std::string::npos);
    EXPECT_NE(errorOf("1\nProperties=species:S:1:pos:R\nSi 0 0 0\n").find("triples"),
              std::string::npos);
    EXPECT_NE(errorOf("1\nProperties=pos:R:3:id:I:1\n0 0 0 1.5\n").find("expected an integer"),
              std::string::npos);
    EXPECT_NE(errorOf("2\nProperties=pos:R:3:id:I:1\n0 0 0 1\n0 0 0 1\n").find("appears twice"),
              std::string::npos);
    EXPECT_NE(errorOf("1000000000000\nc\nSi 0 0 0\n").find("announces"), std::string::npos);
}

TEST(ExtXyz, TruncatedFilesNameTheFrame) {
    faultline::test::TempDir dir;
    std::ifstream in(faultline::test::dataFile("ase322_extxyz_3frames.xyz"));
    const std::string good((std::istreambuf_iterator<char>(in)), {});
    const std::string cut = good.substr(0, good.size() - 200);
    const std::string p = dir.write("cut.xyz", cut);
    try {
        indexDataFile(p);
        FAIL() << "a truncated file was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("particle rows of frame 2"), std::string::npos)
            << e.what();
    }
    // Opened: the two complete frames read, and a note names the one left out.
    auto ds = Dataset::open({p});
    EXPECT_EQ(ds->frameCount(), 2u);
    ASSERT_EQ(ds->notes().size(), 1u);
    EXPECT_NE(ds->notes()[0].find("particle rows of frame 2"), std::string::npos) << ds->notes()[0];
}

// Every truncation and byte change of the ASE file gives an InputError or a frame, never a crash.
TEST(ExtXyz, CorruptedBytesOnlyEverGiveInputErrors) {
    std::ifstream in(faultline::test::dataFile("ase322_extxyz_3frames.xyz"));
    const std::string good((std::istreambuf_iterator<char>(in)), {});
    const std::string first = good.substr(0, good.find("\n6\n") + 1);
    for (std::size_t n = 0; n < first.size(); ++n)
        try {
            parseXyzFrame("t.xyz", first.substr(0, n));
        } catch (const InputError&) {
        }
    for (std::size_t i = 0; i < first.size(); ++i)
        for (char c : {'\0', '\n', ' ', '"', '=', ':', '9', 'x'}) {
            std::string bad = first;
            bad[i] = c;
            try {
                parseXyzFrame("t.xyz", bad);
            } catch (const InputError&) {
            }
        }
}
