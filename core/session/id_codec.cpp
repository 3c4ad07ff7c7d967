#include "core/session/id_codec.hpp"

#include "core/io/base64.hpp"

namespace faultline::core {

std::string packSortedIds(const std::vector<std::int64_t>& ids) {
    std::string bytes;
    bytes.reserve(ids.size() * 2 + 10);
    auto put = [&](std::uint64_t v) {
        while (v >= 0x80) {
            bytes += static_cast<char>((v & 0x7f) | 0x80);
            v >>= 7;
        }
        bytes += static_cast<char>(v);
    };
    if (!ids.empty()) {
        const auto first = static_cast<std::uint64_t>(ids.front());
        put((first << 1) ^
            static_cast<std::uint64_t>(ids.front() >> 63)); // zigzag: may be negative
        for (std::size_t k = 1; k < ids.size(); ++k)
            put(static_cast<std::uint64_t>(ids[k]) - static_cast<std::uint64_t>(ids[k - 1]) - 1);
    }
    return encodeBase64(bytes);
}

std::optional<std::vector<std::int64_t>> unpackSortedIds(std::string_view packed,
                                                         std::string& error) {
    std::string bytes;
    std::size_t offset = 0;
    if (!decodeBase64(packed, bytes, error, offset)) {
        error = "bad base64 at character " + std::to_string(offset) + ": " + error;
        return std::nullopt;
    }
    std::vector<std::int64_t> ids;
    ids.reserve(bytes.size()); // every id takes at least one byte
    std::size_t pos = 0;
    auto get = [&](std::uint64_t& v) {
        v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            if (pos >= bytes.size())
                return false;
            const auto b = static_cast<unsigned char>(bytes[pos++]);
            v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
            if (!(b & 0x80))
                return shift < 63 || (b & 0x7f) <= 1;
        }
        return false;
    };
    std::uint64_t v = 0;
    while (pos < bytes.size()) {
        if (!get(v)) {
            error = "truncated or oversized number at byte " + std::to_string(pos);
            return std::nullopt;
        }
        if (ids.empty()) {
            ids.push_back(static_cast<std::int64_t>((v >> 1) ^ (~(v & 1) + 1)));
        } else {
            const auto prev = static_cast<std::uint64_t>(ids.back());
            const std::uint64_t room = static_cast<std::uint64_t>(INT64_MAX) - prev; // exact
            if (v >= room) {
                error = "id beyond the 64-bit range after " + std::to_string(ids.size()) + " ids";
                return std::nullopt;
            }
            ids.push_back(static_cast<std::int64_t>(prev + 1 + v));
        }
    }
    return ids;
}

} // namespace faultline::core
