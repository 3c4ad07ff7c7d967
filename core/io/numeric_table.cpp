#include "core/io/numeric_table.hpp"

#include "core/io/input_error.hpp"
#include "core/io/newline_count.hpp"

#include <fast_float/fast_float.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace faultline::core {

namespace {

constexpr std::size_t kChunkBytes = 1u << 20;

struct ChunkError {
    std::size_t row = 0; // row within the whole table
    std::string message;
};

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

class RowParser {
  public:
    RowParser(std::vector<TableColumnTarget>& targets, char separator)
        : m_targets(targets), m_separator(separator), m_nonInteger(targets.size(), false) {}

    // Parses one line [p, end) (no newline inside) into row `row`. Returns an error message.
    std::optional<std::string> parseLine(const char* p, const char* end, std::size_t row) {
        const std::size_t columns = m_targets.size();
        for (std::size_t c = 0; c < columns; ++c) {
            while (p < end && isBlank(*p))
                ++p;
            if (c > 0 && m_separator && p < end && *p == m_separator) {
                ++p;
                while (p < end && isBlank(*p))
                    ++p;
            }
            if (p >= end)
                return "expected " + std::to_string(columns) + " values, found " +
                       std::to_string(c);
            const char* tokenStart = p;
            TableColumnTarget& t = m_targets[c];
            switch (t.kind) {
            case TableColumnTarget::Kind::Float: {
                if (*p == '+')
                    ++p;
                // Through double: fast_float's exact fast path covers 15 digits for double and
                // only 7 for float, and most DEM output prints 8 or more.
                double d;
                auto r = fast_float::from_chars(p, end, d);
                const float v = static_cast<float>(d);
                if (r.ec != std::errc() || !endsToken(r.ptr, end))
                    return badToken(tokenStart, end, c, "a number");
                if (t.requireFinite && !std::isfinite(v))
                    return "column '" + t.name + "' must be finite, found " +
                           quoteForError(token(tokenStart, end));
                if (!m_nonInteger[c] &&
                    (d != std::trunc(d) || hasFractionSyntax(tokenStart, r.ptr)))
                    m_nonInteger[c] = true;
                t.floats[row] = v;
                p = r.ptr;
                break;
            }
            case TableColumnTarget::Kind::Int64: {
                std::int64_t v;
                const char* q = parseInt64(p, end, v);
                if (!q)
                    return badToken(tokenStart, end, c, "an integer");
                t.ints[row] = v;
                p = q;
                break;
            }
            case TableColumnTarget::Kind::Skip:
                while (p < end && !isBlank(*p) && *p != m_separator)
                    ++p;
                break;
            }
        }
        while (p < end && (isBlank(*p) || (m_separator && *p == m_separator)))
            ++p;
        if (p < end)
            return "expected " + std::to_string(columns) +
                   " values, found more: " + quoteForError(token(p, end));
        return std::nullopt;
    }

    const std::vector<bool>& nonInteger() const { return m_nonInteger; }

  private:
    bool endsToken(const char* p, const char* end) const {
        return p == end || isBlank(*p) || (m_separator && *p == m_separator);
    }
    std::string_view token(const char* p, const char* end) const {
        const char* q = p;
        while (q < end && !isBlank(*q) && *q != m_separator)
            ++q;
        return {p, static_cast<std::size_t>(q - p)};
    }
    std::string badToken(const char* p, const char* end, std::size_t c,
                         const char* expected) const {
        return "column " + std::to_string(c + 1) + " ('" + m_targets[c].name + "'): expected " +
               expected + ", found " + quoteForError(token(p, end));
    }
    static bool hasFractionSyntax(const char* p, const char* end) {
        for (; p < end; ++p)
            if (*p == '.' || *p == 'e' || *p == 'E')
                return true;
        return false;
    }
    // Integer, or a float token with an integral value (some codes write ids as "12.0").
    const char* parseInt64(const char* p, const char* end, std::int64_t& out) const {
        const char* start = p;
        bool negative = false;
        if (p < end && (*p == '-' || *p == '+'))
            negative = (*p++ == '-');
        std::uint64_t v = 0;
        const char* digits = p;
        while (p < end && *p >= '0' && *p <= '9') {
            const unsigned d = static_cast<unsigned>(*p - '0');
            if (v > (static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) - d) / 10)
                return nullptr;
            v = v * 10 + d;
            ++p;
        }
        if (p != digits && endsToken(p, end)) {
            out = negative ? -static_cast<std::int64_t>(v) : static_cast<std::int64_t>(v);
            return p;
        }
        double d;
        auto r = fast_float::from_chars(start + (*start == '+'), end, d);
        if (r.ec != std::errc() || !endsToken(r.ptr, end) || d != std::trunc(d) ||
            std::fabs(d) > 9.0e15)
            return nullptr;
        out = static_cast<std::int64_t>(d);
        return r.ptr;
    }

    std::vector<TableColumnTarget>& m_targets;
    char m_separator;
    std::vector<bool> m_nonInteger;
};

} // namespace

NumericTableLayout layoutNumericTable(std::string_view text, const NumericTableSpec& spec) {
    NumericTableLayout layout;
    std::vector<std::size_t>& starts = layout.chunkStart;
    starts.push_back(0);
    while (starts.back() + kChunkBytes < text.size()) {
        const std::size_t from = starts.back() + kChunkBytes;
        const void* nl = std::memchr(text.data() + from, '\n', text.size() - from);
        if (!nl)
            break;
        starts.push_back(static_cast<std::size_t>(static_cast<const char*>(nl) - text.data()) + 1);
    }
    starts.push_back(text.size());
    const std::size_t chunks = starts.size() - 1;

    std::vector<std::size_t>& rowStart = layout.chunkRow;
    rowStart.assign(chunks + 1, 0);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t k) {
        const char* p = text.data() + starts[k];
        const char* end = text.data() + starts[k + 1];
        std::size_t lines = countNewlines(p, end);
        if (end > p && end[-1] != '\n')
            ++lines; // last line without a newline
        rowStart[k + 1] = lines;
    });
    for (std::size_t k = 0; k < chunks; ++k)
        rowStart[k + 1] += rowStart[k];
    if (rowStart[chunks] < spec.rows)
        throw InputError(spec.path, InputError::Where::Line, spec.firstLine + rowStart[chunks],
                         "file ends after " + std::to_string(rowStart[chunks]) + " of " +
                             std::to_string(spec.rows) + " particle rows");

    // Cut the layout after row spec.rows.
    std::size_t last = 0; // chunk holding the last wanted row
    while (last + 1 < chunks && rowStart[last + 1] < spec.rows)
        ++last;
    std::size_t end = starts[last];
    for (std::size_t r = rowStart[last]; r < spec.rows; ++r) {
        const void* nl = std::memchr(text.data() + end, '\n', text.size() - end);
        end = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - text.data()) + 1
                 : text.size();
    }
    if (spec.rows == 0) {
        last = 0;
        end = 0;
    }
    starts.resize(last + 2);
    starts.back() = end;
    rowStart.resize(last + 2);
    rowStart.back() = spec.rows;
    layout.end = end;
    layout.rows = spec.rows;
    return layout;
}

void resizeColumnsInParallel(const std::vector<std::vector<float>*>& floats,
                             const std::vector<std::vector<std::int64_t>*>& ints, std::size_t n) {
    tbb::parallel_for(std::size_t(0), floats.size() + ints.size(), [&](std::size_t k) {
        if (k < floats.size())
            floats[k]->resize(n);
        else
            ints[k - floats.size()]->resize(n);
    });
}

void parseNumericTable(std::string_view text, const NumericTableLayout& layout,
                       const NumericTableSpec& spec, std::vector<TableColumnTarget>& targets) {
    const std::vector<std::size_t>& starts = layout.chunkStart;
    const std::vector<std::size_t>& rowStart = layout.chunkRow;
    const std::size_t chunks = starts.size() - 1;
    std::vector<std::optional<ChunkError>> errors(chunks);
    std::vector<std::vector<bool>> nonInteger(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t k) {
        RowParser parser(targets, spec.separator);
        const char* p = text.data() + starts[k];
        const char* end = text.data() + starts[k + 1];
        std::size_t row = rowStart[k];
        while (p < end) {
            const char* nl =
                static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
            const char* lineEnd = nl ? nl : end;
            if (auto err = parser.parseLine(p, lineEnd, row)) {
                errors[k] = ChunkError{row, std::move(*err)};
                return;
            }
            ++row;
            p = nl ? nl + 1 : end;
        }
        nonInteger[k] = parser.nonInteger();
    });
    for (std::size_t k = 0; k < chunks; ++k)
        if (errors[k])
            throw InputError(spec.path, InputError::Where::Line, spec.firstLine + errors[k]->row,
                             errors[k]->message);
    for (std::size_t c = 0; c < targets.size(); ++c) {
        targets[c].sawNonInteger = false;
        for (std::size_t k = 0; k < chunks; ++k)
            if (nonInteger[k][c])
                targets[c].sawNonInteger = true;
    }
}

} // namespace faultline::core
