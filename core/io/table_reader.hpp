// Table reader: CSV or whitespace-separated text with a header row naming the columns.
// x, y, z are required (any case); id and radius (or r, diameter) are optional.
#pragma once

#include "core/model/frame.hpp"

#include <string>
#include <string_view>

namespace faultline::core {

Frame parseTable(const std::string& path, std::string_view text);

} // namespace faultline::core
