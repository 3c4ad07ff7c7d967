// The last step every table reader shares: ids from row numbers when the file has none, the
// default radius (or diameters halved), attribute columns typed (looksLikeIntegerColumn), and
// Frame::finalize with its complaints turned into InputError at the header line.
#pragma once

#include "core/io/numeric_table.hpp"
#include "core/model/frame.hpp"

#include <string>
#include <vector>

namespace faultline::core {

struct ParsedColumns {
    const std::vector<std::string>& names;         // every column of the table
    const std::vector<TableColumnTarget>& targets; // as parsed (sawNonInteger per column)
    std::vector<std::vector<float>>& values;       // values of the attribute columns, by column
    const std::vector<bool>& isAttribute;          // which columns become attributes
    bool hasIds = false;
    enum class Radius { Missing, Radius, Diameter } radius = Radius::Missing;
};

// Completes `frame` (ids, x, y, z, radius already filled by the parse) and finalizes it.
void completeParsedFrame(Frame& frame, ParsedColumns&& parsed, const std::string& path,
                         std::uint64_t headerLine);

} // namespace faultline::core
