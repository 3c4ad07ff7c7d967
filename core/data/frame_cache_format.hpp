// The on-disk layout of one cached frame: a checked header, the validity key, a column table and
// the raw columns (64-byte aligned), so a load is a read into the Frame's vectors, no parsing.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace faultline::core {

// Bump when the layout below changes, or when a reader changes what it makes of the same bytes
// (both make every existing cache file stale).
inline constexpr std::uint32_t kFrameCacheFormatVersion = 2; // 2: constant %g columns stay float

// Why a cache file was not used. Anything but Ok means "parse the source instead".
enum class CachedFrameStatus { Ok, Missing, Stale, Corrupt };

struct CachedFrameRead {
    CachedFrameStatus status = CachedFrameStatus::Missing;
    std::optional<Frame> frame; // finalized, when status is Ok
    std::string detail;         // what was wrong (for logs and tests)
};

// Reads a cache file written by writeCachedFrame. `expectedKey` must equal the key stored in it
// (else Stale). Every size is checked against the file size before anything is allocated, and
// every column against its checksum, so a truncated, corrupt or hostile file is reported, never
// trusted. Never throws for bad file content.
CachedFrameRead readCachedFrame(const std::string& path, std::string_view expectedKey);

// Whether `path` holds a cache file for `expectedKey`: the header, the metadata's checksum and
// the key are checked as readCachedFrame checks them; the column table and the columns are not
// (a read still may find them corrupt). `detail`: what was wrong.
CachedFrameStatus peekCachedFrame(const std::string& path, std::string_view expectedKey,
                                  std::string* detail = nullptr);

// Writes `frame` to `path` atomically (a temporary file in the same folder, then rename).
// Returns the bytes written; throws std::system_error (with errno) when the file system refuses.
// No fsync: a cache needs no durability, and the checksums catch a file torn by a crash.
std::uint64_t writeCachedFrame(const std::string& path, std::string_view key, const Frame& frame);

namespace detail {
// A fast 64-bit checksum (four interleaved multiply-rotate lanes); not cryptographic.
std::uint64_t checksum64(const void* data, std::size_t bytes, std::uint64_t seed);
} // namespace detail

} // namespace faultline::core
