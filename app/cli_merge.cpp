// `faultline merge OUT.csv SHARD.csv...`: the CSVs of replay shards (--frames, --shard) as the
// unsharded run writes them (core/session/csv_merge.hpp).
#include "app/cli.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/session/atomic_file.hpp"
#include "core/session/csv_merge.hpp"

#include <cstdio>
#include <exception>

namespace faultline::app {

int runMerge(const Args& args) {
    if (args.size() < 2 || args[0].rfind("--", 0) == 0) {
        std::fprintf(stderr, "usage: faultline merge OUT.csv SHARD.csv...\n"
                             "Writes the rows of replay shards' CSVs (--frames, --shard) in frame "
                             "order, header once,\nas the unsharded run writes them.\n");
        return 2;
    }
    std::vector<core::CsvShard> shards;
    try {
        for (std::size_t k = 1; k < args.size(); ++k)
            shards.push_back({args[k], core::readFileBytes(args[k])});
        core::writeFileAtomically(args[0], core::mergeShardCsv(shards));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline merge: %s\n", e.what());
        return 1;
    }
    std::printf("%s: merged %zu files\n", args[0].c_str(), shards.size());
    return 0;
}

} // namespace faultline::app
