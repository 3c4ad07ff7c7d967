// `faultline merge`: the CSVs that replay shards (--frames, --shard) wrote, back into the one file
// the unsharded run writes. Rows over time (a first column "frame") are put in frame order, each
// frame from the one shard that has it; files without a frame column (faults) are the same in
// every shard and are written once.
#pragma once

#include <string>
#include <vector>

namespace faultline::core {

struct CsvShard {
    std::string path; // for errors
    std::string text;
};

// The merged text. Throws InputError (path and line) when headers differ, a row is not a
// record of its header (quotes left open, a frame that is no whole number), a frame is in two
// shards, or files without a frame column differ.
std::string mergeShardCsv(const std::vector<CsvShard>& shards);

} // namespace faultline::core
