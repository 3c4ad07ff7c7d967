// Parses the body of a numeric text table (LAMMPS ATOMS section, CSV rows) in parallel:
// the text is split at line boundaries and chunks are parsed concurrently with fast_float.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

// Where the values of one column go.
struct TableColumnTarget {
    enum class Kind { Float, Int64, Skip };
    Kind kind = Kind::Skip;
    float* floats = nullptr;      // Kind::Float: row-indexed destination
    std::int64_t* ints = nullptr; // Kind::Int64: row-indexed destination
    bool requireFinite = false;   // Kind::Float: NaN or Inf is an error (positions, radii)
    std::string name;             // for error messages
    bool sawNonInteger = false;   // out, Kind::Float: some value was not a plain integer
};

struct NumericTableSpec {
    std::string path;            // for errors
    std::uint64_t firstLine = 1; // line number of the first row in the file (1-based)
    std::size_t rows = 0;        // exact number of rows the text must hold
    char separator = 0;          // extra separator besides blanks (',' for CSV), or 0
};

// Where the rows of a table lie: found by counting newlines in parallel, once.
struct NumericTableLayout {
    std::vector<std::size_t> chunkStart; // byte offset of each chunk (a line start); +1 end entry
    std::vector<std::size_t> chunkRow;   // first row of each chunk; +1 entry = rows
    std::size_t end = 0;                 // byte offset just past the last wanted row
    std::size_t rows = 0;                // rows found (<= spec.rows)
};

// Locates the first spec.rows lines of `text` (more may follow; they are not part of the table).
// Throws InputError when the text ends before spec.rows lines.
NumericTableLayout layoutNumericTable(std::string_view text, const NumericTableSpec& spec);

// Parses the rows of a layout, each holding targets.size() values, into the targets.
// Throws InputError naming the file line and the column on any bad token.
void parseNumericTable(std::string_view text, const NumericTableLayout& layout,
                       const NumericTableSpec& spec, std::vector<TableColumnTarget>& targets);

// Allocates several columns of n values at once, in parallel: first-touch page faults of
// large fresh allocations are a good part of a reader's time.
void resizeColumnsInParallel(const std::vector<std::vector<float>*>& floats,
                             const std::vector<std::vector<std::int64_t>*>& ints, std::size_t n);

} // namespace faultline::core
