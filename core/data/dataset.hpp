// Dataset: the ordered frames of one simulation run, from a multi-frame file, a numbered
// series (glob, natural order), a .pvd collection, or LAMMPS per-processor files ('%').
// Frames are indexed once and loaded lazily through a bounded LRU cache (in memory), backed by
// the binary FrameCache on disk.
#pragma once

#include "core/io/frame_source.hpp"
#include "core/model/frame.hpp"
#include "core/motion/strain_spec.hpp"

#include <atomic>
#include <functional>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace faultline::core {

class FrameCache;

// A quarter of the physical memory (sysconf), or 2 GiB when it cannot be told.
std::size_t defaultFrameMemoryBudget();

// Thrown by Dataset::open when its progress callback asked to stop.
class OpenCancelled : public std::runtime_error {
  public:
    OpenCancelled() : std::runtime_error("opening was cancelled") {}
};

class Dataset {
  public:
    Dataset() = default;

    // Expands each pattern ('*', '?', '[..]' globs in natural order; '%' for per-processor
    // pieces) and indexes every file. Throws InputError naming the file at fault. The dataset
    // uses FrameCache::processDefault() as its disk cache.
    // `progress` (optional) hears the fraction of files indexed, and stops the work by returning
    // false (open then throws OpenCancelled).
    using OpenProgress = std::function<bool(double fraction)>;
    static std::shared_ptr<Dataset> open(const std::vector<std::string>& patterns,
                                         const OpenProgress& progress = {});

    // Frames made by a function rather than read from files (synthetic models, tests): `load`
    // returns the finalized frame `index` and may throw like a reader; no disk cache is used.
    static std::shared_ptr<Dataset> fromLoader(std::size_t frameCount,
                                               std::function<Frame(std::size_t index)> load);

    std::size_t frameCount() const { return m_frames.size(); }
    const FrameLocation& location(std::size_t frame) const { return m_frames.at(frame); }
    const std::vector<std::string>& patterns() const { return m_patterns; }
    // What the user should know about how the files were read: a file that ends inside a frame
    // after complete ones (a run still writing, or stopped mid-write) has that frame left out,
    // and a note says so (file, where it stops). Empty for files read whole.
    const std::vector<std::string>& notes() const { return m_notes; }
    std::vector<std::string> files() const;

    // Variables derived from motion (strain.add): every frame the dataset hands out carries
    // their columns after its own, computed against its reference frame (NaN where it has
    // none). Setting a different list makes the cached frames stale: they are derived again,
    // from their own columns, when next asked for. The session keeps this in step with its
    // state (Session::syncDerived).
    void setStrains(std::vector<StrainSpec> strains);

    // Loads (or returns the cached) frame, blocking; safe to call from several threads. Two
    // threads asking for the same frame share one load. Throws InputError from the reader.
    std::shared_ptr<const Frame> frame(std::size_t index) const;
    // The same; `ready` is called once the frame is in memory (at once when it is; other threads
    // asking for it get it from then on), before a frame derived now is written to the disk
    // cache (5-7 ms for a demo frame, more with loads writing at once): a prefetcher wakes the
    // view with it. Not called when the load fails; must not throw.
    std::shared_ptr<const Frame> frame(std::size_t index, const std::function<void()>& ready) const;
    // Frames as read, kept by a pass over the frames between its calls of storeDerivedFrame.
    using BaseFrames = std::map<std::size_t, std::shared_ptr<const Frame>>;
    // For a background pass that readies a whole run for scrubbing: frame `index` derived with
    // the current strains and written to the disk cache, unless it is there (or derived in
    // memory) already, without keeping it in memory. `bases` keeps the frames read for it that
    // a pass in frame order needs again (the next frames' references); the rest are dropped.
    // `bases` is kept within a quarter of the memory budget. True when the frame is stored now
    // or was already; false when it is not (no strains, no disk cache or one that does not keep
    // it, the disk short, frames made by a function, or `cancel` set or the strains changed
    // meanwhile, which the steps check between them). Throws like frame().
    bool storeDerivedFrame(std::size_t index, BaseFrames& bases,
                           const std::atomic<bool>* cancel = nullptr) const;
    // Whether frames derived now go to a disk cache: strains are set, the frames come from files
    // (not from a function), and the cache keeps the first of them (enabled, sources not too
    // small: FrameCache::keeps).
    bool storesDerived() const;
    // Grows with each new list of strains: a pass over the frames starts again.
    std::uint64_t strainsVersion() const;

    // Cached frame or null, never loads (marks the frame most recently used).
    std::shared_ptr<const Frame> cachedFrame(std::size_t index) const;
    // Whether the frame is in memory; leaves the LRU order alone.
    bool isCached(std::size_t index) const;

    // Memory budget of the LRU cache (default: defaultFrameMemoryBudget()). The most recent
    // frame always stays, even over budget.
    void setCacheBudget(std::size_t bytes);
    std::size_t cacheBudget() const { return m_budget.load(); }
    std::size_t cachedBytes() const;
    std::size_t cachedFrameCount() const;

    // The disk cache frames are read from and written to; null: parse every load.
    void setFrameCache(std::shared_ptr<FrameCache> cache);
    std::shared_ptr<FrameCache> frameCache() const;

  private:
    std::vector<std::string> m_patterns;
    std::vector<std::string> m_notes;
    std::vector<FrameLocation> m_frames;
    std::function<Frame(std::size_t)> m_loader; // set by fromLoader

    struct CacheEntry {
        std::size_t index;
        std::shared_ptr<const Frame> frame;
        std::size_t bytes;
        std::uint64_t derived; // the strains version it was derived for; kRead: as read
    };
    static constexpr std::uint64_t kRead = ~std::uint64_t(0);
    std::vector<StrainSpec> m_strains;  // guarded by m_mutex
    std::uint64_t m_strainsVersion = 0; // grows with each new list
    bool currentLocked(const CacheEntry& e) const {
        return e.derived == m_strainsVersion || (e.derived == kRead && m_strains.empty());
    }
    // The frame as read (or any cached version of it: positions and ids are the same), loading
    // it without deriving; cached as read when it was not cached.
    std::shared_ptr<const Frame> baseFrame(std::size_t index) const;
    std::shared_ptr<const Frame> readFrame(std::size_t index) const;
    Frame readFrameValue(std::size_t index) const; // the same, not shared
    void insertLocked(std::size_t index, std::shared_ptr<const Frame> frame, std::uint64_t derived,
                      std::vector<std::shared_ptr<const Frame>>& evicted) const;
    mutable std::mutex m_mutex;          // guards everything below
    mutable std::list<CacheEntry> m_lru; // most recent first
    mutable std::unordered_map<std::size_t, std::list<CacheEntry>::iterator> m_lruIndex;
    mutable std::size_t m_cachedBytes = 0;
    struct Loading {
        std::uint64_t derived;
        std::shared_future<std::shared_ptr<const Frame>> future;
    };
    mutable std::map<std::size_t, Loading> m_loading;
    std::shared_ptr<FrameCache> m_frameCache;
    std::atomic<std::size_t> m_budget{defaultFrameMemoryBudget()};
    // Drops least recently used frames over budget into `evicted`, for the caller to free
    // after it unlocks.
    void evictLocked(std::vector<std::shared_ptr<const Frame>>& evicted) const;
    // The cached entry (any version), marked most recently used; null when not cached.
    const CacheEntry* touchLocked(std::size_t index) const;
};

// Expands a glob pattern ('*', '?', '[..]'); a path with no wildcard is returned as it is.
// Results in natural order (dump.2 before dump.10).
std::vector<std::string> expandGlob(const std::string& pattern);
bool naturalLess(const std::string& a, const std::string& b);

} // namespace faultline::core
