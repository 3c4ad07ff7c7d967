// FramePrefetcher: frames for a UI that must never wait. request() answers at once with the frame
// or "loading"; worker threads load it and the next frames in the direction of travel.
#pragma once

#include "core/data/dataset.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace faultline::core {

enum class FrameStatus { Ready, Loading, Failed };

struct FrameRequestResult {
    FrameStatus status = FrameStatus::Loading;
    std::shared_ptr<const Frame> frame; // when Ready
    std::string error;                  // when Failed: the reader's message (path, line)
};

struct PrefetchSettings {
    std::size_t workers = 2;   // loads in flight at most
    std::size_t lookAhead = 4; // frames prefetched per channel, fewer when memory is short
    bool loop = false;         // prefetch past the last frame wraps to the first (and back)
    // The process's CPU time so far in seconds, which tells whether a view's load leaves a core
    // idle for a prefetch; empty: the process's own (tests give a stand-in).
    std::function<double()> cpuSeconds;
};

class FramePrefetcher {
  public:
    explicit FramePrefetcher(std::shared_ptr<const Dataset> dataset,
                             PrefetchSettings settings = {});
    // Drops queued loads and waits for the running ones (a reader cannot be interrupted).
    ~FramePrefetcher();
    FramePrefetcher(const FramePrefetcher&) = delete;
    FramePrefetcher& operator=(const FramePrefetcher&) = delete;

    // Never blocks on a load. Ready: the frame (from memory). Failed: the load's error (kept
    // until retry()). Loading: it is queued first, ahead of any prefetch. A channel is one
    // consumer (a viewport); its last requests give the direction and stride of travel, and the
    // frames ahead are prefetched, within the dataset's memory budget. Queued loads no channel
    // wants any more are dropped.
    FrameRequestResult request(std::size_t index, std::size_t channel = 0);
    // Like request() but schedules nothing and leaves the channels alone.
    FrameRequestResult peek(std::size_t index) const;

    // A closed viewport: its wishes leave the queue.
    void forgetChannel(std::size_t channel);
    // Drops every queued load and every channel's wishes until its next request (running
    // loads finish and stay in the dataset's cache).
    void cancelPending();
    // Forgets a failed load so the next request() tries again.
    void retry(std::size_t index);
    void setLoop(bool loop);

    // Called on a worker thread after each load ends (loaded or failed), e.g. to wake the UI.
    void setOnLoaded(std::function<void(std::size_t index)> callback);

    // A pass in the background while no view waits for a frame: every frame derived with the
    // dataset's strains into the disk cache (Dataset::storeDerivedFrame), so that scrubbing
    // anywhere later reads derived frames instead of deriving them. In frame order from the one a
    // view shows when the pass starts (then from the first), one frame at a time on one worker,
    // never while a view's load runs. It runs only while the dataset stores derived frames and the
    // whole run, at the size of the frames in memory, fits in half the disk cache's budget (a
    // larger run would push its own first frames out). Starts again when the strains change. Off by
    // default; cancelPending() turns it off.
    void setBackgroundDerivation(bool on);
    struct BackgroundProgress {
        std::size_t done = 0;  // frames of the pass readied (derived now or found stored)
        std::size_t total = 0; // the run's frames
        bool running = false;  // working, or with frames left to do and allowed to go on
        // Why a pass with frames left does not run, for the UI to say: the frame cache is off,
        // refused a frame (a short disk, an unwritable folder: FrameCache::problem() says), or
        // the run is too large for it (known once a frame is in memory). None while it runs,
        // once done, and for sources too small to cache (they derive as fast as they read).
        enum class Held { None, CacheOff, CacheRefusesWrites, RunTooLarge };
        Held held = Held::None;
        std::uint64_t runBytes = 0;    // RunTooLarge: the run at the size of the frames in memory
        std::uint64_t budgetBytes = 0; // RunTooLarge: half the frame cache's budget
    };
    BackgroundProgress backgroundProgress() const;

    // Queued plus running loads (a background frame included).
    std::size_t pendingCount() const;
    // Waits until nothing is queued or running (for tests and the CLI; a background pass is not
    // waited for); false on timeout.
    bool waitIdle(std::chrono::milliseconds timeout) const;

    const std::shared_ptr<const Dataset>& dataset() const { return m_dataset; }

  private:
    struct Channel {
        std::size_t index = 0;
        long direction = 1; // +1 forward, -1 backward
        std::size_t stride = 1;
        bool seen = false;
    };

    std::shared_ptr<const Dataset> m_dataset;
    PrefetchSettings m_settings;

    mutable std::mutex m_mutex;
    mutable std::condition_variable m_wake; // workers: work or stop
    mutable std::condition_variable m_idle; // waitIdle
    std::map<std::size_t, Channel> m_channels;
    std::deque<std::size_t> m_queue; // next load first
    std::set<std::size_t> m_running;
    std::size_t m_finishing = 0; // loads ended whose callback is running
    std::map<std::size_t, std::string> m_errors;
    std::function<void(std::size_t)> m_onLoaded;
    bool m_stop = false;
    std::vector<std::thread> m_workers;

    struct Background {
        bool on = false;
        bool started = false;
        std::uint64_t version = 0;      // the dataset's strains version the pass is for
        std::size_t start = 0;          // the first frame of the pass (a view's at its start)
        std::size_t next = 0, done = 0; // frames visited (start, start + 1, ... around the end)
        bool running = false;
        bool useful = false;         // the dataset stores derived frames (asked once a pass)
        bool refused = false;        // the cache refused a frame: the pass ended there
        Dataset::BaseFrames bases;   // kept between frames: the next ones' references
        Dataset::BaseFrames dropped; // of a pass started again, to free with the lock released
    };
    Background m_background;
    std::atomic<bool> m_cancel{false}; // a background frame stops between its steps
    // Whether a worker should ready the next frame in the background now (starts the pass again
    // when the strains changed).
    bool backgroundDueLocked();
    // Whether a view shows frame `index` now (a channel's current frame).
    bool wantedLocked(std::size_t index) const;
    // Whether a worker should start the queue's next load now. A prefetch waits while a frame a
    // view waits for loads, which then has every core (on 2 cores, a prefetch beside it made
    // it take twice as long), unless that load leaves a core idle (a gzip file inflates on one
    // thread): the prefetch then starts on it.
    bool nextLoadDueLocked() const;
    // A view's load runs and the next load is a prefetch (held unless m_hold.released).
    bool prefetchBehindViewLocked() const;
    // Watches the process's CPU time while a prefetch is held back: a window of it using a core
    // less than the machine has releases the prefetch.
    void watchHoldLocked();
    struct Hold {
        bool watching = false, released = false;
        std::chrono::steady_clock::time_point since;
        double cpuSeconds = 0; // the process's CPU time at `since`
    };
    Hold m_hold;
    // Whether the whole run fits in half the disk cache's budget; `runBytes` / `budgetBytes`:
    // the two sides (0 when no frame is in memory yet or there is no cache).
    bool backgroundFitsLocked(std::uint64_t* runBytes = nullptr,
                              std::uint64_t* budgetBytes = nullptr) const;
    void runBackground(std::unique_lock<std::mutex>& lock);

    void rebuildQueueLocked();
    std::vector<std::size_t> wishesLocked(const Channel& channel, std::size_t depth) const;
    std::size_t prefetchDepthLocked() const;
    void work();
};

} // namespace faultline::core
