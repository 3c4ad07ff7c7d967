// Dataset: the ordered frames of one simulation run, from a multi-frame file, a numbered
// series (glob, natural order), a .pvd collection, or LAMMPS per-processor files ('%').
// Frames are indexed once and loaded lazily through a bounded LRU cache.
#pragma once

#include "core/io/frame_source.hpp"
#include "core/model/frame.hpp"

#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace faultline::core {

class Dataset {
  public:
    Dataset() = default;

    // Expands each pattern ('*', '?', '[..]' globs in natural order; '%' for per-processor
    // pieces) and indexes every file. Throws InputError naming the file at fault.
    static std::shared_ptr<Dataset> open(const std::vector<std::string>& patterns);

    std::size_t frameCount() const { return m_frames.size(); }
    const FrameLocation& location(std::size_t frame) const { return m_frames.at(frame); }
    const std::vector<std::string>& patterns() const { return m_patterns; }
    std::vector<std::string> files() const;

    // Loads (or returns the cached) frame; safe to call from several threads.
    std::shared_ptr<const Frame> frame(std::size_t index) const;
    // Cached frame or null, never loads.
    std::shared_ptr<const Frame> cachedFrame(std::size_t index) const;

    void setCacheBudget(std::size_t bytes);
    std::size_t cacheBudget() const { return m_budget; }
    std::size_t cachedBytes() const;

  private:
    std::vector<std::string> m_patterns;
    std::vector<FrameLocation> m_frames;

    struct CacheEntry {
        std::size_t index;
        std::shared_ptr<const Frame> frame;
        std::size_t bytes;
    };
    mutable std::mutex m_mutex;
    mutable std::list<CacheEntry> m_lru; // most recent first
    mutable std::size_t m_cachedBytes = 0;
    std::size_t m_budget = std::size_t(2) << 30;
    void evictLocked() const;
};

// Expands a glob pattern ('*', '?', '[..]'); a path with no wildcard is returned as it is.
// Results in natural order (dump.2 before dump.10).
std::vector<std::string> expandGlob(const std::string& pattern);
bool naturalLess(const std::string& a, const std::string& b);

} // namespace faultline::core
