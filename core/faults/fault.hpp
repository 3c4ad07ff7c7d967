// Fault: a named, coloured set of particle ids with free-text notes. Labels follow particle ids
// across frames; `ids` is kept sorted and unique so membership tests are a binary search.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace faultline::core {

struct Fault {
    std::string name;
    std::array<float, 3> color{1.0f, 0.5f, 0.0f};
    std::string notes;
    bool visible = true;
    std::vector<std::int64_t> ids; // sorted, unique

    bool contains(std::int64_t id) const;
    // Adds ids (any order, duplicates allowed); returns the ids that were new.
    std::vector<std::int64_t> add(std::vector<std::int64_t> more);
    // Removes ids; returns the ids that were members.
    std::vector<std::int64_t> remove(std::vector<std::int64_t> less);
    bool operator==(const Fault&) const = default;
};

// Sorts and removes duplicates.
void normalizeIds(std::vector<std::int64_t>& ids);

// Order-sensitive hash of member ids (pass them sorted, as Fault::ids keeps them): the key of
// whatever is cached per membership (surfaces, metric series, colourings).
std::uint64_t hashMemberIds(std::span<const std::int64_t> ids);

} // namespace faultline::core
