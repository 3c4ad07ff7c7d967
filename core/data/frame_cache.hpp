// FrameCache: parsed frames kept on disk ($XDG_CACHE_HOME/faultline/frames) so a frame parsed
// once loads again with no parsing. Keyed by the sources' paths, byte ranges, sizes and mtimes.
#pragma once

#include "core/io/frame_source.hpp"
#include "core/model/frame.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace faultline::core {

struct FrameCacheSettings {
    bool enabled = true;
    std::string folder;                          // empty: defaultFrameCacheFolder()
    std::uint64_t budgetBytes = 10ull << 30;     // the folder's size; oldest files go first
    std::uint64_t minSourceBytes = 1ull << 20;   // smaller sources parse faster than a cache write
    std::uint64_t minFreeDiskBytes = 1ull << 30; // never fill the disk past this
};

// $XDG_CACHE_HOME/faultline/frames, else ~/.cache/faultline/frames; empty when neither is known.
std::string defaultFrameCacheFolder();

// What identifies the source state of a frame: format, timestep, and for each piece its absolute
// path, byte range, size and mtime (ns). nullopt when a source cannot be stat'ed.
std::optional<std::string> frameCacheKey(const FrameLocation& location);

namespace detail {
// What identifies a cached frame's sources (frame_cache.cpp).
struct SourceState {
    std::string key;      // identity + the sources' sizes and mtimes: what makes a file valid
    std::string identity; // which frame it is: names the file
    std::uint64_t sourceBytes = 0;
};
} // namespace detail

class FrameCache {
  public:
    explicit FrameCache(FrameCacheSettings settings);

    // The cache Dataset::open attaches: default settings, disabled when the environment says
    // FAULTLINE_FRAME_CACHE=0 (or off/no/false). Replace it with setProcessDefault (null: none).
    static std::shared_ptr<FrameCache> processDefault();
    static void setProcessDefault(std::shared_ptr<FrameCache> cache);

    // The frame from the cache when a valid file exists, else parsed from its source (throws
    // InputError like loadFrame) and written to the cache. Failing to write never fails a load:
    // the problem is logged once to stderr and kept in problem(). Safe from several threads.
    Frame fetch(const FrameLocation& location);

    // The cached frame, or nullopt (missing, stale or corrupt: a bad file is deleted).
    std::optional<Frame> lookup(const FrameLocation& location);
    // Writes `frame` for `location` unless disabled, too small, or the disk is short (false);
    // never throws.
    bool store(const FrameLocation& location, const Frame& frame);

    // A frame derived from `location` and the frames at `others` (strain from motion against
    // reference frames), `variant` naming what was derived: valid while every source is as it
    // was. Same rules as lookup / store.
    std::optional<Frame> lookupDerived(const FrameLocation& location,
                                       const std::vector<FrameLocation>& others,
                                       const std::string& variant);
    bool storeDerived(const FrameLocation& location, const std::vector<FrameLocation>& others,
                      const std::string& variant, const Frame& frame);
    // Whether lookupDerived would find the frame, from the file's header and key alone (neither
    // the column table nor the columns are checked: a background pass asks this of every frame
    // of a run, and a read still rejects a bad file). A corrupt header: the file is deleted.
    bool holdsDerived(const FrameLocation& location, const std::vector<FrameLocation>& others,
                      const std::string& variant);

    // Whether frames of `location` (as read or derived) are kept: the cache is enabled, takes
    // writes, and their sources are not too small (minSourceBytes). The disk's room is not asked
    // (store() answers that).
    bool keeps(const FrameLocation& location) const;
    // The file that holds (or would hold) a location's frame; empty when disabled.
    std::string pathFor(const FrameLocation& location) const;
    // Deletes every cache file in the folder.
    void clear();

    const FrameCacheSettings& settings() const { return m_settings; }
    bool enabled() const { return m_settings.enabled && !m_settings.folder.empty(); }
    // Whether writes are refused after a failed one (a short disk, an unwritable folder).
    bool writesRefused() const;
    // The last problem (unwritable folder, full disk, corrupt file), "" when none.
    std::string problem() const;

    struct Stats {
        std::uint64_t hits = 0, misses = 0, rejected = 0, writes = 0, writeFailures = 0;
    };
    Stats stats() const;

  private:
    FrameCacheSettings m_settings;
    mutable std::mutex m_mutex; // guards the fields below
    std::string m_problem;
    bool m_warned = false;
    bool m_writesDisabled = false;              // after a write the file system refused for good
    std::optional<std::uint64_t> m_folderBytes; // known after the first write
    Stats m_stats;

    void noteProblem(const std::string& message, bool disableWrites);
    // Deletes a cache file found corrupt, notes it and counts it.
    void dropCorrupt(const std::string& path, const std::string& detail);
    std::optional<Frame> lookupState(const std::optional<detail::SourceState>& state);
    bool storeState(const std::optional<detail::SourceState>& state, const Frame& frame);
    // Writes not refused for good, and sources not too small (keeps, storeState).
    bool keepsState(const std::optional<detail::SourceState>& state) const;
    void evictOverBudget(const std::string& keep);
};

} // namespace faultline::core
