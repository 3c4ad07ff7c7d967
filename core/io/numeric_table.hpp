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
    float* floats = nullptr;        // Kind::Float: row-indexed destination
    std::int64_t* ints = nullptr;   // Kind::Int64: row-indexed destination
    bool requireFinite = false;     // Kind::Float: NaN or Inf is an error (positions, radii)
    std::string name;               // for error messages
    bool sawNonInteger = false;     // out, Kind::Float: some value was not a plain integer
};

struct NumericTableSpec {
    std::string path;             // for errors
    std::uint64_t firstLine = 1;  // line number of the first row in the file (1-based)
    std::size_t rows = 0;         // exact number of rows the text must hold
    char separator = 0;           // extra separator besides blanks (',' for CSV), or 0
};

// Parses exactly spec.rows lines of `text`, each holding targets.size() values.
// Throws InputError naming the file line and the column on any bad token or count mismatch.
void parseNumericTable(std::string_view text, const NumericTableSpec& spec,
                       std::vector<TableColumnTarget>& targets);

// The byte offset just past the end of line `count` counted from `from` (or text.size() when
// the text ends first); `linesFound` receives how many complete or partial lines were skipped.
std::size_t skipLines(std::string_view text, std::size_t from, std::size_t count,
                      std::size_t& linesFound);

} // namespace faultline::core
