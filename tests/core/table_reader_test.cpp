#include "core/io/input_error.hpp"
#include "core/io/table_reader.hpp"
#include "core/model/dataset.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

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
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", ""); }), "t.csv: empty file: expected a header row naming columns x, y, z");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "a,b,c\n1,2,3\n"); }),
              "t.csv:1: header must name columns x, y and z, found 'a,b,c'");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,3\n1,2\n"); }), "t.csv:3: expected 3 values, found 2");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,3\n\n1,2,3\n"); }), "t.csv:3: expected 3 values, found 0");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z,x\n"); }), "t.csv:1: column 'x' appears twice");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "x,y,z\n1,2,-inf\n"); }), "t.csv:2: column 'z' must be finite, found '-inf'");
    EXPECT_EQ(inputErrorOf([] { parseTable("t.csv", "id,x,y,z\n1,0,0,0\n1,0,0,0\n"); }), "t.csv:1: particle id 1 appears twice");
}

TEST(TableReader, FixtureDemeWheel) {
    auto ds = Dataset::open({faultline::test::dataFile("deme_wheel_output_0000.csv")});
    auto f = ds->frame(0);
    EXPECT_EQ(f->size(), 26208u);
    EXPECT_FALSE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(), std::vector<std::string>{"absv"});
}
