#include "core/faults/fault.hpp"

#include <algorithm>
#include <iterator>

namespace faultline::core {

void normalizeIds(std::vector<std::int64_t>& ids) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

bool Fault::contains(std::int64_t id) const {
    return std::binary_search(ids.begin(), ids.end(), id);
}

std::vector<std::int64_t> Fault::add(std::vector<std::int64_t> more) {
    normalizeIds(more);
    std::vector<std::int64_t> added;
    std::set_difference(more.begin(), more.end(), ids.begin(), ids.end(),
                        std::back_inserter(added));
    if (!added.empty()) {
        std::vector<std::int64_t> merged;
        merged.reserve(ids.size() + added.size());
        std::merge(ids.begin(), ids.end(), added.begin(), added.end(), std::back_inserter(merged));
        ids = std::move(merged);
    }
    return added;
}

std::vector<std::int64_t> Fault::remove(std::vector<std::int64_t> less) {
    normalizeIds(less);
    std::vector<std::int64_t> removed;
    std::set_intersection(less.begin(), less.end(), ids.begin(), ids.end(),
                          std::back_inserter(removed));
    if (!removed.empty()) {
        std::vector<std::int64_t> kept;
        kept.reserve(ids.size() - removed.size());
        std::set_difference(ids.begin(), ids.end(), removed.begin(), removed.end(),
                            std::back_inserter(kept));
        ids = std::move(kept);
    }
    return removed;
}

std::uint64_t hashMemberIds(std::span<const std::int64_t> ids) {
    std::uint64_t h = 0xcbf29ce484222325ull ^ ids.size();
    for (std::int64_t id : ids) {
        h ^= static_cast<std::uint64_t>(id);
        h *= 0x100000001b3ull;
        h ^= h >> 29;
    }
    return h;
}

} // namespace faultline::core
