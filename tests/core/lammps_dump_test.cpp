#include "core/data/dataset.hpp"
#include "core/io/frame_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/lammps_dump.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>

using namespace faultline::core;
using faultline::test::inputErrorOf;
using faultline::test::TempDir;

namespace {

std::string header(long atoms, const std::string& columns,
                   const std::string& box = "pp pp pp\n0 10\n0 20\n0 30\n", long timestep = 100) {
    return "ITEM: TIMESTEP\n" + std::to_string(timestep) + "\nITEM: NUMBER OF ATOMS\n" +
           std::to_string(atoms) + "\nITEM: BOX BOUNDS " + box + "ITEM: ATOMS " + columns + "\n";
}

Frame parse(const std::string& text) { return parseLammpsDumpFrame("t.dump", text); }

} // namespace

TEST(LammpsDump, ColumnsInAnyOrderWithRadius) {
    Frame f = parse(header(2, "x radius id type z y c_strain") +
                    "1 0.5 7 1 3 2 0.25\n4 0.75 3 2 6 5 1e-3\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.timestep, 100);
    EXPECT_EQ(f.ids[0], 7);
    EXPECT_EQ(f.ids[1], 3);
    EXPECT_FLOAT_EQ(f.x[1], 4);
    EXPECT_FLOAT_EQ(f.y[1], 5);
    EXPECT_FLOAT_EQ(f.z[1], 6);
    EXPECT_FLOAT_EQ(f.radius[0], 0.5f);
    EXPECT_FALSE(f.radiusIsDefault);
    ASSERT_EQ(f.attributes.size(), 2u);
    EXPECT_EQ(f.attributes[0].name, "type");
    EXPECT_TRUE(f.attributes[0].isInteger());
    EXPECT_EQ(f.attributes[1].name, "c_strain");
    EXPECT_FALSE(f.attributes[1].isInteger());
    EXPECT_DOUBLE_EQ(f.attributes[1].max, 0.25);
    EXPECT_EQ(f.rowOf(3), 1u);
    EXPECT_TRUE(f.box.known);
    EXPECT_DOUBLE_EQ(f.box.hi[2], 30);
}

TEST(LammpsDump, BracketedNamesKeptAndDiameterHalved) {
    Frame f = parse(header(1, "id x y z diameter f_force[1] c_s[2]") + "1 0 0 0 2 3.5 -1\n");
    EXPECT_FLOAT_EQ(f.radius[0], 1.0f);
    ASSERT_NE(f.attribute("f_force[1]"), nullptr);
    ASSERT_NE(f.attribute("c_s[2]"), nullptr);
    EXPECT_EQ(f.attribute("c_s[2]")->min, -1);
}

TEST(LammpsDump, NoRadiusGivesDefaultFlagged) {
    Frame f = parse(header(1, "id x y z") + "1 0 0 0\n");
    EXPECT_TRUE(f.radiusIsDefault);
    EXPECT_FLOAT_EQ(f.radius[0], kDefaultRadius);
}

TEST(LammpsDump, NoIdUsesRowNumbers) {
    Frame f = parse(header(2, "x y z") + "0 0 0\n1 1 1\n");
    EXPECT_TRUE(f.idsAreRowNumbers);
    EXPECT_EQ(f.ids[1], 1);
}

TEST(LammpsDump, UnwrappedPositionsPreferredAfterPlain) {
    Frame f = parse(header(1, "id xu yu zu") + "1 11 -2 3\n");
    EXPECT_FLOAT_EQ(f.x[0], 11);
    EXPECT_FLOAT_EQ(f.y[0], -2);
    Frame g = parse(header(1, "id x y z xu yu zu") + "1 1 2 3 11 12 13\n");
    EXPECT_FLOAT_EQ(g.x[0], 1);
    ASSERT_NE(g.attribute("xu"), nullptr); // the unused set stays as columns
}

TEST(LammpsDump, ScaledOrthogonal) {
    Frame f = parse(header(1, "id xs ys zs") + "1 0.5 0.25 1\n");
    EXPECT_FLOAT_EQ(f.x[0], 5);
    EXPECT_FLOAT_EQ(f.y[0], 5);
    EXPECT_FLOAT_EQ(f.z[0], 30);
}

TEST(LammpsDump, TriclinicBoundsAndScaledPositions) {
    // Cell: xlo=0 xhi=10, ylo=0 yhi=10, zlo=0 zhi=10, xy=2, xz=1, yz=-3.
    // Bounding box written by LAMMPS: xlo_b = 0 + min(0,2,1,3) = 0; xhi_b = 10 + max(0,2,1,3) = 13;
    // ylo_b = 0 + min(0,-3) = -3; yhi_b = 10 + max(0,-3) = 10.
    const std::string box = "xy xz yz pp pp ff\n0 13 2\n-3 10 1\n0 10 -3\n";
    Frame f = parse(header(1, "id xsu ysu zsu", box) + "1 0.5 0.5 0.5\n");
    EXPECT_TRUE(f.box.triclinic);
    EXPECT_DOUBLE_EQ(f.box.lo[0], 0);
    EXPECT_DOUBLE_EQ(f.box.hi[0], 10);
    EXPECT_DOUBLE_EQ(f.box.lo[1], 0);
    EXPECT_DOUBLE_EQ(f.box.hi[1], 10);
    EXPECT_TRUE(f.box.periodic[0]);
    EXPECT_FALSE(f.box.periodic[2]);
    // x = 0 + 5 + 0.5*2 + 0.5*1 = 6.5; y = 0 + 5 + 0.5*(-3) = 3.5; z = 5
    EXPECT_FLOAT_EQ(f.x[0], 6.5f);
    EXPECT_FLOAT_EQ(f.y[0], 3.5f);
    EXPECT_FLOAT_EQ(f.z[0], 5.0f);
}

TEST(LammpsDump, UnitsTimeItemsAndWindowsLineEnds) {
    std::string text = "ITEM: UNITS\r\nlj\r\nITEM: TIME\r\n0.5\r\n" + header(1, "id x y z radius") +
                       "1 1 2 3 0.5\r\n";
    Frame f = parse(text);
    EXPECT_EQ(f.size(), 1u);
    EXPECT_FLOAT_EQ(f.radius[0], 0.5f);
}

TEST(LammpsDump, ErrorsNameLineAndWhat) {
    const std::string h = header(2, "id x y z");
    // Header is 9 lines, rows start at line 10.
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 0 zz 0\n"); }),
              "t.dump:11: column 3 ('y'): expected a number, found 'zz'");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 0 0\n"); }),
              "t.dump:11: expected 4 values, found 3");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 0 0 0 9\n"); }),
              "t.dump:11: expected 4 values, found more: '9'");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 nan 0 0\n"); }),
              "t.dump:11: column 'x' must be finite, found 'nan'");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 inf 0 0\n"); }),
              "t.dump:11: column 'x' must be finite, found 'inf'");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n1.5 0 0 0\n"); }),
              "t.dump:11: column 1 ('id'): expected an integer, found '1.5'");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n1 0 0 0\n"); }),
              "t.dump:1: particle id 1 appears twice");
    EXPECT_NE(inputErrorOf([&] {
                  parse(header(1, "id a b c") + "1 0 0 0\n");
              }).find("no position columns"),
              std::string::npos);
    EXPECT_EQ(inputErrorOf([&] { parse("ITEM: TIMESTEP\nabc\n"); }),
              "t.dump:2: expected the timestep (an integer), found 'abc'");
    EXPECT_EQ(inputErrorOf([&] { parse("ITEM: TIMESTEP\n1\nITEM: NUMBER OF ATOMS\n-4\n"); }),
              "t.dump:4: expected the number of atoms (an integer >= 0), found '-4'");
    EXPECT_EQ(inputErrorOf([&] { parse("ITEM: TIMESTEP\n1\nITEM: BOGUS\n"); }),
              "t.dump:3: unknown section 'ITEM: BOGUS'");
    EXPECT_EQ(inputErrorOf([&] { parse("ITEM: TIMESTEP\n1\n"); }),
              "t.dump:3: file ends where an ITEM: line was expected");
    EXPECT_EQ(inputErrorOf([&] { parse(h + "1 0 0 0\n2 0 0 0\n3 0 0 0\n"); }),
              "t.dump:12: more rows than the 2 announced");
}

TEST(LammpsDump, HugeAtomCountRefusedBeforeAllocating) {
    const std::string text = header(1000000000000LL, "id x y z") + "1 0 0 0\n";
    const std::string msg = inputErrorOf([&] { parse(text); });
    EXPECT_EQ(msg, "t.dump:10: NUMBER OF ATOMS is 1000000000000 but only 8 bytes follow");
}

TEST(LammpsDump, RowsTooShortForTheirCountNameTheRow) {
    // Two lines exist but hold too few bytes for 4 values each: the short row is named.
    EXPECT_EQ(inputErrorOf([&] { parse(header(2, "id x y z") + "1 0 0 0\n2\n"); }),
              "t.dump:11: expected 4 values, found 1");
}

TEST(LammpsDump, BinaryGarbageIsAClearError) {
    TempDir dir;
    std::string garbage = "ITEM: TIMESTEP\n";
    for (int i = 0; i < 3000; ++i)
        garbage += static_cast<char>((i * 7919) % 256);
    const std::string p = dir.write("garbage.dump", garbage);
    EXPECT_THROW(Dataset::open({p}), InputError);
}

// Walkthrough of issue 41: a damaged .lammpstrj that did not start with ITEM: was read as a CSV
// table and refused for its header ("must name columns x, y and z"); its name says what it
// should be, so the dump reader says what is wrong.
TEST(LammpsDump, ANamedTrajectoryThatIsNoDumpGetsTheDumpReadersError) {
    TempDir dir;
    const std::string p = dir.write("broken.lammpstrj", "this, is, not, a, dump\n1,2,3,4,5\n");
    EXPECT_EQ(detectFormat(p), FileFormat::LammpsDump);
    try {
        Dataset::open({p});
        FAIL() << "opened";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.lammpstrj:1: expected an 'ITEM:' line"),
                  std::string::npos)
            << e.what();
    }
    // The same text named as a table is a table's problem.
    EXPECT_EQ(detectFormat(dir.write("broken.csv", "this, is, not, a, dump\n1,2,3,4,5\n")),
              FileFormat::Table);
}

TEST(LammpsDump, MultiFrameIndexAndLazyLoad) {
    TempDir dir;
    std::string text;
    for (int t = 0; t < 3; ++t)
        text += header(2, "id x y z", "pp pp pp\n0 1\n0 1\n0 1\n", t * 10) + "1 " +
                std::to_string(t) + " 0 0\n2 0 0 0\n\n";
    const std::string p = dir.write("multi.lammpstrj", text);
    auto ds = Dataset::open({p});
    ASSERT_EQ(ds->frameCount(), 3u);
    EXPECT_EQ(ds->location(2).timestep, 20);
    EXPECT_EQ(ds->location(1).pieces[0].firstLine, 13u); // 9 header lines, 2 rows, 1 blank
    EXPECT_FLOAT_EQ(ds->frame(2)->x[0], 2.0f);
    EXPECT_FLOAT_EQ(ds->frame(1)->x[0], 1.0f);
}

TEST(LammpsDump, TruncatedMultiFrameNamesTheFrame) {
    TempDir dir;
    const std::string p = dir.write(
        "cut.dump", header(2, "id x y z") + "1 0 0 0\n2 0 0 0\n" +
                        header(3, "id x y z", "pp pp pp\n0 1\n0 1\n0 1\n", 200) + "1 0 0 0\n");
    // Indexed alone, the cut is an error naming the line and the frame.
    const std::string msg = inputErrorOf([&] { indexDataFile(p); });
    EXPECT_NE(msg.find(":22: file ends after 1 of 3 particle rows of timestep 200"),
              std::string::npos)
        << msg;
    // Opened, the frame before it reads, and a note says what was left out (a run still writing,
    // or one stopped by a job's time limit, keeps its complete frames).
    auto ds = Dataset::open({p});
    ASSERT_EQ(ds->frameCount(), 1u);
    EXPECT_EQ(ds->frame(0)->size(), 2u);
    ASSERT_EQ(ds->notes().size(), 1u);
    EXPECT_NE(ds->notes()[0].find("ends inside frame 1 (line 22: file ends after 1 of 3 particle "
                                  "rows of timestep 200)"),
              std::string::npos)
        << ds->notes()[0];
    EXPECT_NE(ds->notes()[0].find("cut.dump"), std::string::npos);
}

TEST(LammpsDump, AHeaderCutShortKeepsTheFramesBeforeIt) {
    TempDir dir;
    const std::string box = "pp pp pp\n0 1\n0 1\n0 1\n";
    const std::string p = dir.write("cut.dump", header(1, "id x y z", box, 0) + "1 0 0 0\n" +
                                                    header(1, "id x y z", box, 10) + "1 0 0 0\n" +
                                                    "ITEM: TIMESTEP\n20\nITEM: NUMBER OF ATOMS\n");
    auto ds = Dataset::open({p});
    EXPECT_EQ(ds->frameCount(), 2u);
    ASSERT_EQ(ds->notes().size(), 1u);
    EXPECT_NE(ds->notes()[0].find("ends inside frame 2 (its header stops at line"),
              std::string::npos)
        << ds->notes()[0];
    // A header broken before the end of the file is no cut: an error, as before.
    const std::string bad = dir.write("bad.dump", header(1, "id x y z", box, 0) + "1 0 0 0\n" +
                                                      "ITEM: TIMESTEP\nten\n" +
                                                      header(1, "id x y z", box, 20) + "1 0 0 0\n");
    EXPECT_THROW(Dataset::open({bad}), InputError);
}

TEST(LammpsDump, AGzipDumpCutShortKeepsItsCompleteFrames) {
    // A dump.gz copied or written only in part: the frames before the cut read, whichever frame
    // the decompressor's read-ahead was in when the stream stopped; a single cut frame is an
    // error.
    TempDir dir;
    std::string text;
    for (int t = 0; t < 6; ++t) {
        text += header(4000, "id x y z", "pp pp pp\n0 1\n0 1\n0 1\n", t * 100);
        for (int i = 0; i < 4000; ++i)
            text += std::to_string(i + 1) + " 0." + std::to_string(1000 + (i * 7 + t) % 9000) +
                    " 0.5 0.25\n";
    }
    const std::string p = dir.file("run.dump.gz");
    gzFile g = gzopen(p.c_str(), "wb");
    gzwrite(g, text.data(), static_cast<unsigned>(text.size()));
    gzclose(g);
    const auto whole = std::filesystem::file_size(p);
    std::filesystem::resize_file(p, whole * 3 / 4);
    auto ds = Dataset::open({p});
    EXPECT_GE(ds->frameCount(), 3u);
    EXPECT_LE(ds->frameCount(), 5u);
    for (std::size_t k = 0; k < ds->frameCount(); ++k)
        EXPECT_EQ(ds->frame(k)->size(), 4000u) << "frame " << k;
    ASSERT_EQ(ds->notes().size(), 1u);
    EXPECT_NE(ds->notes()[0].find("compressed stream is truncated"), std::string::npos)
        << ds->notes()[0];
}

TEST(LammpsDump, GzipReadThroughZlib) {
    TempDir dir;
    const std::string text = header(2, "id x y z radius") + "1 0 0 0 1\n2 3 0 0 1\n";
    const std::string p = dir.file("a.dump.gz");
    gzFile g = gzopen(p.c_str(), "wb");
    gzwrite(g, text.data(), static_cast<unsigned>(text.size()));
    gzclose(g);
    auto ds = Dataset::open({p});
    EXPECT_EQ(ds->frame(0)->size(), 2u);
    EXPECT_FLOAT_EQ(ds->frame(0)->x[1], 3.0f);
}

TEST(LammpsDump, TruncatedGzipIsAnError) {
    TempDir dir;
    std::string text = header(3000, "id x y z");
    for (int i = 0; i < 3000; ++i)
        text += std::to_string(i + 1) + " 0.123456 0.234567 0.345678\n";
    const std::string p = dir.file("a.dump.gz");
    gzFile g = gzopen(p.c_str(), "wb");
    gzwrite(g, text.data(), static_cast<unsigned>(text.size()));
    gzclose(g);
    std::filesystem::resize_file(p, std::filesystem::file_size(p) / 2);
    EXPECT_THROW(Dataset::open({p}), InputError);
}

TEST(LammpsDump, NumberedSeriesInNaturalOrder) {
    TempDir dir;
    for (int t : {100, 20, 3})
        dir.write("dump." + std::to_string(t) + ".txt",
                  header(1, "id x y z", "pp pp pp\n0 1\n0 1\n0 1\n", t) + "1 0 0 0\n");
    auto ds = Dataset::open({dir.file("dump.*.txt")});
    ASSERT_EQ(ds->frameCount(), 3u);
    EXPECT_EQ(ds->location(0).timestep, 3);
    EXPECT_EQ(ds->location(1).timestep, 20);
    EXPECT_EQ(ds->location(2).timestep, 100);
}

TEST(LammpsDump, PerProcessorPiecesMerge) {
    TempDir dir;
    const std::string box = "pp pp pp\n0 1\n0 1\n0 1\n";
    for (int t : {0, 5}) {
        dir.write("d." + std::to_string(t) + ".0",
                  header(2, "id x y z c", box, t) + "1 0 0 0 1\n2 0 0 0 2\n");
        dir.write("d." + std::to_string(t) + ".1",
                  header(1, "id x y z c", box, t) + "3 0 0 0 2.5\n");
    }
    auto ds = Dataset::open({dir.file("d.*.%")});
    ASSERT_EQ(ds->frameCount(), 2u);
    auto f = ds->frame(1);
    EXPECT_EQ(f->timestep, 5);
    EXPECT_EQ(f->size(), 3u);
    EXPECT_EQ(f->rowOf(3), 2u);
    const AttributeColumn* c = f->attribute("c");
    ASSERT_NE(c, nullptr);
    EXPECT_FALSE(c->isInteger()); // piece 0 had integers only, piece 1 a fraction
    EXPECT_DOUBLE_EQ(c->max, 2.5);
}

TEST(LammpsDump, FixtureImageVfMultiframe) {
    auto ds = Dataset::open({faultline::test::dataFile("lammps_image_vf_multiframe.lammpstrj")});
    ASSERT_EQ(ds->frameCount(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        auto f = ds->frame(k);
        EXPECT_EQ(f->size(), 7u);
        EXPECT_TRUE(f->radiusIsDefault);
        EXPECT_EQ(f->attributeNames(),
                  (std::vector<std::string>{"mol", "type", "q", "ix", "iy", "iz", "vx", "vy", "vz",
                                            "fx", "fy", "fz"}));
    }
}

TEST(LammpsDump, FixtureLiggghtsPackingDetectedByContent) {
    const std::string p = faultline::test::dataFile("liggghts_packing_22410.particles");
    EXPECT_EQ(detectFormat(p), FileFormat::LammpsDump);
    auto ds = Dataset::open({p});
    ASSERT_EQ(ds->frameCount(), 1u);
    auto f = ds->frame(0);
    EXPECT_EQ(f->size(), 22410u);
    EXPECT_FALSE(f->radiusIsDefault);
    auto [mn, mx] = std::minmax_element(f->radius.begin(), f->radius.end());
    EXPECT_NEAR(*mn, 0.001, 1e-6);
    EXPECT_NEAR(*mx, 0.021, 1e-6);
}

// Old-style dumps (LAMMPS before 2009; pizza.py reads them): "ITEM: BOX BOUNDS" without flags and
// "ITEM: ATOMS" naming no columns. Rows are LAMMPS' atom style, id type xs ys zs, with image
// flags ix iy iz when the run asked for them; the frame says the names were assumed. The file
// follows that documented layout (tests/data/MANIFEST.md).
TEST(LammpsDump, OldStyleDumpWithoutColumnNamesIsReadAsAtomStyle) {
    auto ds = Dataset::open({faultline::test::dataFile("lammps_oldstyle_atom_scaled.dump")});
    ASSERT_EQ(ds->frameCount(), 2u);
    EXPECT_EQ(ds->location(1).timestep, 1000);
    const auto a = ds->frame(0);
    ASSERT_EQ(a->size(), 4u);
    EXPECT_TRUE(a->columnsAssumed);
    EXPECT_TRUE(a->radiusIsDefault);
    EXPECT_EQ(a->attributeNames(), (std::vector<std::string>{"type"}));
    EXPECT_TRUE(a->box.known);
    EXPECT_EQ(a->box.periodic, (std::array<bool, 3>{false, false, false}));
    // Scaled by the box [0 20] x [-5 5] x [0 10].
    EXPECT_EQ(a->x[0], 5.0f);
    EXPECT_EQ(a->y[0], 0.0f);
    EXPECT_EQ(a->z[0], 1.0f);
    EXPECT_EQ(a->x[3], 15.0f);
    EXPECT_EQ(a->y[3], 2.5f);
    EXPECT_EQ(a->z[3], 9.0f);
    EXPECT_EQ(a->ids, (std::vector<std::int64_t>{1, 2, 3, 4}));
    const auto b = ds->frame(1);
    EXPECT_TRUE(b->columnsAssumed);
    EXPECT_EQ(b->attributeNames(), (std::vector<std::string>{"type", "ix", "iy", "iz"}));
    EXPECT_EQ(b->x[1], 1.0f);
    EXPECT_EQ(b->z[3], 9.5f);
    EXPECT_EQ(b->attribute("iy")->ints[2], -1);
    // Rows of another width are not guessed at.
    const std::string old =
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS\n0 1\n0 1\n0 1\n"
        "ITEM: ATOMS\n";
    EXPECT_EQ(inputErrorOf([&] { parse(old + "1 1 0.5 0.5\n"); }),
              "t.dump:10: 'ITEM: ATOMS' names no columns, so this is read as an old-style dump "
              "(LAMMPS' atom style): expected rows of 5 values (id type xs ys zs) or 8 (id type "
              "xs ys zs ix iy iz), found 4");
    EXPECT_EQ(inputErrorOf([&] { parse(old + "1 1 0.5 0.5 0.5 0 0\n"); }).substr(0, 8), "t.dump:1");
    EXPECT_EQ(parse(old + "7 1 0.5 0.5 0.5\n").ids.front(), 7);
    // Scaled positions need the box: an old-style frame without one says so.
    EXPECT_NE(
        inputErrorOf([&] {
            parse("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS\n1 1 0.5 0.5 0.5\n");
        }).find("scaled positions need 'ITEM: BOX BOUNDS'"),
        std::string::npos);
}
