#include "core/session/csv_merge.hpp"

#include "core/io/input_error.hpp"

#include <algorithm>
#include <charconv>
#include <map>

namespace faultline::core {

namespace {

struct Record {
    std::string_view text; // without its line end
    std::size_t line = 0;  // where it starts, from 1
};

// Records of a CSV text: a line end inside double quotes belongs to the field.
std::vector<Record> records(const CsvShard& shard) {
    std::vector<Record> out;
    const std::string& t = shard.text;
    std::size_t start = 0, line = 1, startLine = 1;
    bool quoted = false;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const char c = t[i];
        if (c == '"')
            quoted = !quoted;
        else if (c == '\n') {
            if (!quoted) {
                std::size_t end = i;
                if (end > start && t[end - 1] == '\r')
                    --end;
                out.push_back({std::string_view(t).substr(start, end - start), startLine});
                start = i + 1;
                startLine = line + 1;
            }
            ++line;
        }
    }
    if (quoted)
        throw InputError(shard.path, InputError::Where::Line, startLine,
                         "a quoted field is never closed (the file ends inside it)");
    if (start < t.size())
        out.push_back({std::string_view(t).substr(start), startLine});
    return out;
}

} // namespace

std::string mergeShardCsv(const std::vector<CsvShard>& shards) {
    if (shards.empty())
        throw std::invalid_argument("merge: no files to merge");
    std::vector<std::vector<Record>> all;
    for (const CsvShard& s : shards) {
        all.push_back(records(s));
        if (all.back().empty())
            throw InputError(s.path, "empty file: expected a CSV header line");
    }
    const std::string_view header = all[0][0].text;
    for (std::size_t k = 1; k < shards.size(); ++k)
        if (all[k][0].text != header)
            throw InputError(shards[k].path, InputError::Where::Line, 1,
                             "header " + quoteForError(all[k][0].text, 80) + " differs from " +
                                 shards[0].path + "'s " + quoteForError(header, 80) +
                                 ": these are not shards of one export");
    std::string out(header);
    out += '\n';
    const bool overTime = header == "frame" || header.rfind("frame,", 0) == 0;
    if (!overTime) {
        for (std::size_t k = 1; k < shards.size(); ++k)
            if (all[k].size() != all[0].size() ||
                !std::equal(all[k].begin(), all[k].end(), all[0].begin(),
                            [](const Record& a, const Record& b) { return a.text == b.text; }))
                throw InputError(shards[k].path,
                                 "differs from " + shards[0].path +
                                     ": a CSV without a frame column is the same in every shard");
        for (std::size_t r = 1; r < all[0].size(); ++r) {
            out += all[0][r].text;
            out += '\n';
        }
        return out;
    }
    // frame -> the shard that has it, then the rows in file order.
    std::map<std::size_t, std::size_t> owner;
    struct Row {
        std::size_t frame;
        std::string_view text;
    };
    std::vector<Row> rows;
    for (std::size_t k = 0; k < shards.size(); ++k)
        for (std::size_t r = 1; r < all[k].size(); ++r) {
            const Record& rec = all[k][r];
            if (rec.text.empty())
                continue;
            const std::size_t comma = rec.text.find(',');
            const std::string_view field = rec.text.substr(0, comma);
            std::size_t frame = 0;
            const auto [end, ec] =
                std::from_chars(field.data(), field.data() + field.size(), frame);
            if (ec != std::errc() || end != field.data() + field.size())
                throw InputError(shards[k].path, InputError::Where::Line, rec.line,
                                 "expected a frame number in the first column, got " +
                                     quoteForError(field));
            const auto [it, fresh] = owner.emplace(frame, k);
            if (!fresh && it->second != k)
                throw InputError(shards[k].path, InputError::Where::Line, rec.line,
                                 "frame " + std::to_string(frame) + " is also in " +
                                     shards[it->second].path +
                                     ": shards must cover different frames");
            rows.push_back({frame, rec.text});
        }
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Row& a, const Row& b) { return a.frame < b.frame; });
    for (const Row& r : rows) {
        out += r.text;
        out += '\n';
    }
    return out;
}

} // namespace faultline::core
