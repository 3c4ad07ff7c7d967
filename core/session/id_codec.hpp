// Compact particle id lists for session files: sorted unique ids as gaps (LEB128 varints) in
// base64. A 100,000-member fault takes ~130 kB instead of ~700 kB of JSON numbers, and loads in
// a millisecond instead of tens.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

// `ids` must be sorted and unique (Fault::ids are).
std::string packSortedIds(const std::vector<std::int64_t>& ids);

// The ids, or nullopt with `error` set on bad base64, a truncated varint, an overflow, or more
// ids than the text can hold.
std::optional<std::vector<std::int64_t>> unpackSortedIds(std::string_view packed,
                                                         std::string& error);

} // namespace faultline::core
