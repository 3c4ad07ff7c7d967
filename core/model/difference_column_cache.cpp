#include "core/model/difference_column_cache.hpp"

#include "core/model/frame_difference.hpp"

#include <cassert>

namespace faultline::core {

namespace {
// Same object, not merely the same address: a freed frame's address can be reused.
bool sameFrame(const std::weak_ptr<const Frame>& held, const std::shared_ptr<const Frame>& f) {
    return !held.owner_before(f) && !f.owner_before(held) && !held.expired();
}
} // namespace

template <typename Compute>
std::shared_ptr<const AttributeColumn>
DifferenceColumnCache::lookup(const std::shared_ptr<const Frame>& now,
                              const std::shared_ptr<const Frame>& reference,
                              std::string_view variable, bool isDisplacement, Compute compute) {
    assert(now && reference);
    {
        std::lock_guard lock(m_mutex);
        for (auto it = m_entries.begin(); it != m_entries.end(); ++it)
            if (it->isDisplacement == isDisplacement && it->variable == variable &&
                sameFrame(it->now, now) && sameFrame(it->reference, reference)) {
                m_entries.splice(m_entries.begin(), m_entries, it);
                return it->column;
            }
    }
    // Computed without the lock: two threads may both compute it; either result is right.
    auto column = std::make_shared<const AttributeColumn>(compute());
    std::lock_guard lock(m_mutex);
    m_entries.remove_if([](const Entry& e) { return e.now.expired() || e.reference.expired(); });
    m_entries.push_front({now, reference, std::string(variable), isDisplacement, column});
    while (m_entries.size() > m_capacity)
        m_entries.pop_back();
    return column;
}

std::shared_ptr<const AttributeColumn>
DifferenceColumnCache::change(const std::shared_ptr<const Frame>& now,
                              const std::shared_ptr<const Frame>& reference,
                              std::string_view variable) {
    return lookup(now, reference, variable, false,
                  [&] { return variableChange(*now, *reference, variable); });
}

std::shared_ptr<const AttributeColumn>
DifferenceColumnCache::displacement(const std::shared_ptr<const Frame>& now,
                                    const std::shared_ptr<const Frame>& reference) {
    return lookup(now, reference, "", true, [&] { return displacementSince(*now, *reference); });
}

void DifferenceColumnCache::clear() {
    std::lock_guard lock(m_mutex);
    m_entries.clear();
}

} // namespace faultline::core
