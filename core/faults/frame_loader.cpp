#include "core/faults/frame_loader.hpp"

#include <charconv>
#include <stdexcept>

namespace faultline::core {

namespace {

// A whole non-negative decimal number, or nothing.
bool readCount(std::string_view text, std::size_t& out) {
    if (text.empty())
        return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size();
}

} // namespace

std::vector<std::size_t> FrameSelection::frames(std::size_t frameCount) const {
    std::vector<std::size_t> out;
    for (std::size_t f = first; f < frameCount && f <= last; ++f)
        if (f % shards == shard)
            out.push_back(f);
    return out;
}

std::string FrameSelection::describe() const {
    std::string out;
    if (first != 0 || last != std::numeric_limits<std::size_t>::max())
        out = "frames " + std::to_string(first) + ".." +
              (last == std::numeric_limits<std::size_t>::max() ? std::string("end")
                                                               : std::to_string(last));
    if (shards > 1)
        out += (out.empty() ? "" : ", ") + std::string("shard ") + std::to_string(shard + 1) + "/" +
               std::to_string(shards);
    return out.empty() ? "every frame" : out;
}

FrameSelection parseFrameRange(const std::string& text) {
    const std::size_t colon = text.find(':');
    FrameSelection s;
    if (colon == std::string::npos ||
        !readCount(std::string_view(text).substr(0, colon), s.first) ||
        !readCount(std::string_view(text).substr(colon + 1), s.last))
        throw std::invalid_argument("--frames expects FIRST:LAST (frame numbers from 0, both "
                                    "included), got \"" +
                                    text + "\"");
    if (s.first > s.last)
        throw std::invalid_argument("--frames " + text + ": the first frame is after the last");
    return s;
}

FrameSelection parseFrameShard(const std::string& text) {
    const std::size_t slash = text.find('/');
    std::size_t k = 0, n = 0;
    if (slash == std::string::npos || !readCount(std::string_view(text).substr(0, slash), k) ||
        !readCount(std::string_view(text).substr(slash + 1), n))
        throw std::invalid_argument("--shard expects K/N (shard K of N, from 1), got \"" + text +
                                    "\"");
    if (n < 1 || k < 1 || k > n)
        throw std::invalid_argument("--shard " + text + ": K must lie between 1 and N");
    FrameSelection s;
    s.shard = k - 1;
    s.shards = n;
    return s;
}

} // namespace faultline::core
