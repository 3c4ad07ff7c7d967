// DifferenceColumnCache: the last few difference columns by (frame, reference frame, variable),
// so a viewport drawn every UI frame computes one only when its frames or variable change.
#pragma once

#include "core/model/frame.hpp"

#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace faultline::core {

class DifferenceColumnCache {
  public:
    explicit DifferenceColumnCache(std::size_t capacity = 8) : m_capacity(capacity) {}

    // variableChange(*now, *reference, variable), computed once per distinct inputs. Throws
    // std::invalid_argument when `now` lacks the variable. Safe from several threads.
    std::shared_ptr<const AttributeColumn> change(const std::shared_ptr<const Frame>& now,
                                                  const std::shared_ptr<const Frame>& reference,
                                                  std::string_view variable);
    // displacementSince(*now, *reference), computed once per distinct inputs.
    std::shared_ptr<const AttributeColumn>
    displacement(const std::shared_ptr<const Frame>& now,
                 const std::shared_ptr<const Frame>& reference);

    void clear();

  private:
    struct Entry {
        std::weak_ptr<const Frame> now, reference; // expired: the frames are gone, so is this
        std::string variable;                      // empty for displacement
        bool isDisplacement = false;
        std::shared_ptr<const AttributeColumn> column;
    };
    std::size_t m_capacity;
    std::mutex m_mutex;
    std::list<Entry> m_entries; // most recent first

    template <typename Compute>
    std::shared_ptr<const AttributeColumn>
    lookup(const std::shared_ptr<const Frame>& now, const std::shared_ptr<const Frame>& reference,
           std::string_view variable, bool isDisplacement, Compute compute);
};

} // namespace faultline::core
