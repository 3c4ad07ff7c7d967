#include "core/data/dataset.hpp"
#include "core/io/input_error.hpp"
#include "core/io/newline_count.hpp"
#include "core/io/table_reader.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace faultline::core;

using faultline::test::inputErrorOf;

TEST(TableReader, CsvWithIdRadiusAndAttributes) {
    Frame f = parseTable("t.csv", "id,x,y,z,radius,strain\n5,1,2,3,0.5,0.1\n6,4,5,6,0.25,0.2\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.ids[1], 6);
    EXPECT_FLOAT_EQ(f.z[1], 6);
    EXPECT_FLOAT_EQ(f.radius[1], 0.25f);
    ASSERT_EQ(f.attributes.size(), 1u);
    EXPECT_EQ(f.attributes[0].name, "strain");
}

TEST(TableReader, WhitespaceUpperCaseQuotedAndTrailingBlankLines) {
    Frame f = parseTable("t.txt", "# \"X\"  Y\tZ  r\n1 2 3 0.5\n  4 5 6 0.5  \n\n\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_FLOAT_EQ(f.x[1], 4);
    EXPECT_TRUE(f.idsAreRowNumbers);
}

TEST(TableReader, Errors) {
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", ""); }),
              "t.csv: empty file: expected a header row naming columns x, y, z");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "a,b,c\n1,2,3\n"); }),
              "t.csv:1: header must name columns x, y and z (accepted: x y z; Points:0..2; "
              "coordinates:0..2; Pos.x/Pos.y/Pos.z; pos_x; position_x; position:0; units in "
              "brackets are ignored), found 'a, b, c'");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,3\n1,2\n"); }),
              "t.csv:3: expected 3 values, found 2");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,3\n\n1,2,3\n"); }),
              "t.csv:3: expected 3 values, found 0");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z,x\n"); }),
              "t.csv:1: column 'x' appears twice");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,-inf\n"); }),
              "t.csv:2: column 'z' must be finite, found '-inf'");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "id,x,y,z\n1,0,0,0\n1,0,0,0\n"); }),
              "t.csv:1: particle id 1 appears twice");
}

TEST(TableReader, FixtureDemeWheel) {
    auto ds = Dataset::open({faultline::test::dataFile("deme_wheel_output_0000.csv")});
    auto f = ds->frame(0);
    EXPECT_EQ(f->size(), 26208u);
    EXPECT_FALSE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(), std::vector<std::string>{"absv"});
}

TEST(TableReader, ParaViewCsvWithQuotedPointsColumns) {
    // What ParaView 5.11's SaveData writes for points with arrays: quoted names, Points:0..2.
    Frame f =
        parseTable("pv.csv", "\"id\",\"radius\",\"strain\",\"Points:0\",\"Points:1\",\"Points:2\"\n"
                             "3,0.5,0.01,1.5,2.5,3.5\n4,0.25,0.02,4,5,6\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.ids[0], 3);
    EXPECT_FLOAT_EQ(f.x[0], 1.5f);
    EXPECT_FLOAT_EQ(f.z[1], 6.0f);
    EXPECT_FLOAT_EQ(f.radius[1], 0.25f);
    EXPECT_EQ(f.attributeNames(), std::vector<std::string>{"strain"});
    Frame g =
        parseTable("pv.csv", "\"coordinates:0\",\"coordinates:1\",\"coordinates:2\"\n1,2,3\n");
    EXPECT_FLOAT_EQ(g.y[0], 2.0f);
}

TEST(TableReader, DualSphysicsSemicolonsAndUnits) {
    // PartCSV layout: semicolons, units in brackets; the shown names keep the units.
    Frame f = parseTable("part.csv", "Pos.x [m];Pos.y [m];Pos.z [m];Idp;Vel.x [m/s];Rhop [kg/m^3]\n"
                                     "0.1;0.2;0.3;7;1.5;1000\n0.4;0.5;0.6;9;-1;1001\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.ids[1], 9);
    EXPECT_FLOAT_EQ(f.x[1], 0.4f);
    EXPECT_FLOAT_EQ(f.z[0], 0.3f);
    EXPECT_EQ(f.attributeNames(), (std::vector<std::string>{"Vel.x [m/s]", "Rhop [kg/m^3]"}));
    EXPECT_TRUE(f.radiusIsDefault);
}

// Issue 37: DualSPHysics' PartCSV ends every line, the header's too, with ';'.
TEST(TableReader, DualSphysicsTrailingSemicolonIsNoColumn) {
    Frame f = parseTable("part.csv", "Pos.x [m];Pos.y [m];Pos.z [m];Idp;Type;\n"
                                     "0.1;0.2;0.3;7;2;\n0.4;0.5;0.6;9;1;\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.ids[1], 9);
    EXPECT_EQ(f.attributeNames(), (std::vector<std::string>{"Type"}));
    EXPECT_EQ(f.attribute("Type")->value(0), 2.0);
}

// Issue 37: Yade's export.textExt(..., format='x_y_z_r_attrs', attrs=[...]) writes the
// attributes' values (a vector's three) after the radius, unnamed.
TEST(TableReader, YadeTextExtAttributesBecomeNumberedColumns) {
    Frame f = parseTable("yade.txt", "#format x_y_z_r_attrs\n"
                                     "1 2 3 0.5 7 0.1 0.2 0.3\n4 5 6 0.25 8 -0.1 0 1e-3\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_FLOAT_EQ(f.radius[1], 0.25f);
    EXPECT_EQ(f.attributeNames(),
              (std::vector<std::string>{"attr_1", "attr_2", "attr_3", "attr_4"}));
    EXPECT_FLOAT_EQ(f.attribute("attr_4")->floats[1], 1e-3f);
}

// Found by the fuzzer: a '#format ..._attrs' file that ends inside its comment lines read past
// its end. It is a table of no rows.
TEST(TableReader, AFormatLineWithOnlyCommentsAfterItHasNoRows) {
    EXPECT_EQ(parseTable("yade.txt", "#format x_y_z_r_attrs\n# x y z r id").size(), 0u);
    EXPECT_EQ(parseTable("yade.txt", std::string("#format x_y_z_r_attrs\n# s fro7\tm a "
                                                 "journal0.0033196\x0b\0\0\0: tw",
                                                 59))
                  .size(),
              0u);
    const Frame f = parseTable("yade.txt", "#format x_y_z_r_attrs\n# x y z r id\n1 2 3 0.5 7");
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{7}));
}

TEST(TableReader, YadeFormatLineNamesTheColumns) {
    // Yade's export.text(): "#format x_y_z_r", then blank-separated rows.
    Frame f = parseTable("yade.txt", "#format x_y_z_r\n1 2 3 0.5\n4 5 6 0.25\n");
    ASSERT_EQ(f.size(), 2u);
    EXPECT_FLOAT_EQ(f.y[1], 5.0f);
    EXPECT_FLOAT_EQ(f.radius[0], 0.5f);
    EXPECT_FALSE(f.radiusIsDefault);
    Frame g = parseTable("yade.txt", "#format id_x_y_z_r_matId\n7 1 2 3 0.5 1\n");
    EXPECT_EQ(g.ids[0], 7);
    EXPECT_EQ(g.attributeNames(), std::vector<std::string>{"matId"});
}

TEST(TableReader, TabSeparatedNamesWithSpaces) {
    Frame f = parseTable("t.tsv", "X [m]\tY [m]\tZ [m]\tshear strain\n1\t2\t3\t0.5\n");
    ASSERT_EQ(f.size(), 1u);
    EXPECT_FLOAT_EQ(f.z[0], 3.0f);
    EXPECT_EQ(f.attributeNames(), std::vector<std::string>{"shear strain"});
}

TEST(TableReader, FixtureWrittenByParaView511SaveData) {
    // Written by pvpython 5.11 (Debian's python3-paraview): SaveData of 12 points with arrays
    // id, radius, strain.
    auto ds = Dataset::open({faultline::test::dataFile("paraview511_savedata_points.csv")});
    auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 12u);
    EXPECT_EQ(f->ids[0], 100);
    EXPECT_EQ(f->ids[11], 111);
    EXPECT_FLOAT_EQ(f->x[1], 0.5f);
    EXPECT_FLOAT_EQ(f->y[1], 1.25f);
    EXPECT_FLOAT_EQ(f->z[1], 1.875f);
    EXPECT_FLOAT_EQ(f->radius[5], 0.5f);
    EXPECT_EQ(f->attributeNames(), std::vector<std::string>{"strain"});
}

TEST(TableReader, NewlineCountMatchesAByteCountAtEveryLengthAndOffset) {
    // Text longer than the SSE2 count's 255 steps of 16 bytes (where its byte lanes are summed),
    // newlines at every byte position, every start offset and length around those steps.
    std::string text;
    for (int i = 0; i < 9000; ++i)
        text += (i % 7 == 0 || i % 13 == 0 || (i > 4000 && i < 4200)) ? '\n' : 'x';
    for (std::size_t offset : {0, 1, 5, 15, 16, 17}) {
        for (std::size_t length : {0, 1, 15, 16, 17, 4079, 4080, 4081, 4096, 8191, 8983}) {
            const char* p = text.data() + offset;
            ASSERT_LE(offset + length, text.size());
            EXPECT_EQ(countNewlines(p, p + length),
                      static_cast<std::size_t>(std::count(p, p + length, '\n')))
                << "offset " << offset << ", length " << length;
        }
    }
    const std::string all(5000, '\n');
    EXPECT_EQ(countNewlines(all.data(), all.data() + all.size()), all.size());
}
