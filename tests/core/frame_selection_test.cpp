// replay --frames / --shard and `faultline merge`: which frames a selection holds, how its
// arguments are read, and how shards' CSVs go back together (tests/batch/shards_match.sh runs
// the whole thing on a generated model).
#include "core/faults/frame_loader.hpp"
#include "core/io/input_error.hpp"
#include "core/session/csv_merge.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;

TEST(FrameSelection, RangesAndShardsHoldTheFramesTheySay) {
    EXPECT_TRUE(FrameSelection{}.everything());
    EXPECT_EQ(FrameSelection{}.frames(3), (std::vector<std::size_t>{0, 1, 2}));
    const FrameSelection range = parseFrameRange("2:4");
    EXPECT_EQ(range.frames(10), (std::vector<std::size_t>{2, 3, 4}));
    EXPECT_EQ(range.frames(4), (std::vector<std::size_t>{2, 3}));
    EXPECT_EQ(range.describe(), "frames 2..4");
    const FrameSelection shard = parseFrameShard("2/3");
    EXPECT_EQ(shard.frames(8), (std::vector<std::size_t>{1, 4, 7}));
    EXPECT_EQ(shard.describe(), "shard 2/3");
    EXPECT_EQ(parseFrameShard("1/1"), FrameSelection{});
    for (const char* bad : {"", "3", "a:b", "4:2", "-1:3", "1:2:3", " 1:2"})
        EXPECT_THROW(parseFrameRange(bad), std::invalid_argument) << bad;
    for (const char* bad : {"", "0/3", "4/3", "1/0", "x/2", "2", "1/2/3"})
        EXPECT_THROW(parseFrameShard(bad), std::invalid_argument) << bad;
}

TEST(CsvMerge, RowsGoBackInFrameOrderHeaderOnce) {
    const std::string header = "frame,fault,count\n";
    const std::string a = header + "0,F1,3\n0,F2,4\n2,F1,5\n2,F2,6\n";
    const std::string b = header + "1,F1,7\n1,\"F,2\",8\n3,F1,9\n";
    EXPECT_EQ(mergeShardCsv({{"a.csv", a}, {"b.csv", b}}),
              header + "0,F1,3\n0,F2,4\n1,F1,7\n1,\"F,2\",8\n2,F1,5\n2,F2,6\n3,F1,9\n");
    // A shard without rows (no frames of its own) adds nothing.
    EXPECT_EQ(mergeShardCsv({{"a.csv", a}, {"empty.csv", header}}), a);
    // Files without a frame column are the same in every shard: written once.
    const std::string faults = "id,fault\n1,F1\n2,F1\n";
    EXPECT_EQ(mergeShardCsv({{"a.csv", faults}, {"b.csv", faults}}), faults);
}

TEST(CsvMerge, RefusesFilesThatAreNotShardsOfOneExportNamingFileAndLine) {
    auto refused = [](const std::vector<CsvShard>& shards, const std::string& message) {
        try {
            mergeShardCsv(shards);
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    const std::string h = "frame,fault\n";
    refused({{"a.csv", h + "0,F1\n"}, {"b.csv", "frame,other\n1,F1\n"}}, "b.csv:1: header");
    refused({{"a.csv", h + "0,F1\n"}, {"b.csv", h + "1,F1\n0,F2\n"}},
            "b.csv:3: frame 0 is also in a.csv");
    refused({{"a.csv", h + "0,F1\nx,F2\n"}}, "a.csv:3: expected a frame number");
    refused({{"a.csv", h + "0,\"F1\n"}}, "a.csv:2: a quoted field is never closed");
    refused({{"a.csv", "id,fault\n1,F1\n"}, {"b.csv", "id,fault\n2,F1\n"}}, "b.csv: differs");
    refused({{"a.csv", ""}}, "a.csv: empty file");
    EXPECT_THROW(mergeShardCsv({}), std::invalid_argument);
}
