#include "core/data/frame_prefetcher.hpp"

#include "core/data/frame_cache.hpp"

#include <tbb/task_arena.h>

#include <time.h>

#include <algorithm>
#include <exception>
#include <limits>

namespace faultline::core {

namespace {
// A step larger than this is a jump, not travel: prefetch one by one from where it landed.
constexpr std::size_t kMaxStride = 8;
// How long a prefetch held back for a view's load watches for an idle core at a time.
constexpr std::chrono::milliseconds kHoldWindow{20};

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}
} // namespace

FramePrefetcher::FramePrefetcher(std::shared_ptr<const Dataset> dataset, PrefetchSettings settings)
    : m_dataset(std::move(dataset)), m_settings(settings) {
    const std::size_t workers = std::max<std::size_t>(1, m_settings.workers);
    m_workers.reserve(workers);
    for (std::size_t k = 0; k < workers; ++k)
        m_workers.emplace_back([this] { work(); });
}

FramePrefetcher::~FramePrefetcher() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
        m_cancel = true;
        m_queue.clear();
    }
    m_wake.notify_all();
    for (auto& t : m_workers)
        t.join();
}

FrameRequestResult FramePrefetcher::request(std::size_t index, std::size_t channel) {
    const std::size_t count = m_dataset ? m_dataset->frameCount() : 0;
    if (index >= count)
        return {FrameStatus::Failed, nullptr,
                "frame " + std::to_string(index) + " does not exist (the data has " +
                    std::to_string(count) + " frames)"};
    auto frame = m_dataset->cachedFrame(index);
    std::lock_guard lock(m_mutex);
    Channel& c = m_channels[channel];
    const bool moved = !c.seen || c.index != index;
    if (moved && c.seen) {
        // Distance each way (around the ends when looping); the shorter way is the direction.
        const std::size_t unreachable = std::numeric_limits<std::size_t>::max();
        std::size_t forward = index > c.index ? index - c.index : unreachable;
        std::size_t backward = index < c.index ? c.index - index : unreachable;
        if (m_settings.loop) {
            forward = (index + count - c.index) % count;
            backward = (c.index + count - index) % count;
        }
        c.direction = forward <= backward ? 1 : -1;
        c.stride = std::min(forward, backward);
        if (c.stride > kMaxStride)
            c.stride = 1;
    }
    c.index = index;
    c.seen = true;

    FrameRequestResult result;
    bool scheduled = true;
    if (frame) {
        result.status = FrameStatus::Ready;
        result.frame = std::move(frame);
    } else if (auto e = m_errors.find(index); e != m_errors.end()) {
        result.status = FrameStatus::Failed;
        result.error = e->second;
    } else {
        result.status = FrameStatus::Loading;
        scheduled = m_running.count(index) ||
                    std::find(m_queue.begin(), m_queue.end(), index) != m_queue.end();
    }
    if (moved || !scheduled)
        rebuildQueueLocked();
    return result;
}

FrameRequestResult FramePrefetcher::peek(std::size_t index) const {
    FrameRequestResult result;
    if (!m_dataset || index >= m_dataset->frameCount()) {
        result.status = FrameStatus::Failed;
        result.error = "frame " + std::to_string(index) + " does not exist";
        return result;
    }
    if (auto frame = m_dataset->cachedFrame(index)) {
        result.status = FrameStatus::Ready;
        result.frame = std::move(frame);
        return result;
    }
    std::lock_guard lock(m_mutex);
    if (auto e = m_errors.find(index); e != m_errors.end()) {
        result.status = FrameStatus::Failed;
        result.error = e->second;
    }
    return result;
}

void FramePrefetcher::forgetChannel(std::size_t channel) {
    std::lock_guard lock(m_mutex);
    m_channels.erase(channel);
    rebuildQueueLocked();
}

void FramePrefetcher::cancelPending() {
    std::lock_guard lock(m_mutex);
    m_channels.clear();
    m_queue.clear();
    m_background.on = false;
    m_cancel = true;
    if (m_running.empty() && m_finishing == 0)
        m_idle.notify_all();
}

void FramePrefetcher::retry(std::size_t index) {
    std::lock_guard lock(m_mutex);
    m_errors.erase(index);
}

void FramePrefetcher::setLoop(bool loop) {
    std::lock_guard lock(m_mutex);
    m_settings.loop = loop;
    rebuildQueueLocked();
}

void FramePrefetcher::setOnLoaded(std::function<void(std::size_t)> callback) {
    std::lock_guard lock(m_mutex);
    m_onLoaded = std::move(callback);
}

std::size_t FramePrefetcher::pendingCount() const {
    std::lock_guard lock(m_mutex);
    return m_queue.size() + m_running.size() + m_finishing + (m_background.running ? 1 : 0);
}

void FramePrefetcher::setBackgroundDerivation(bool on) {
    std::lock_guard lock(m_mutex);
    m_background.on = on;
    m_cancel = !on;
    if (on)
        m_wake.notify_all();
}

FramePrefetcher::BackgroundProgress FramePrefetcher::backgroundProgress() const {
    std::lock_guard lock(m_mutex);
    BackgroundProgress p;
    if (!m_dataset)
        return p;
    p.total = m_dataset->frameCount();
    const bool current =
        m_background.started && m_dataset->strainsVersion() == m_background.version;
    p.done = current ? m_background.done : 0;
    std::uint64_t runBytes = 0, budgetBytes = 0;
    const bool fits = backgroundFitsLocked(&runBytes, &budgetBytes);
    p.running = m_background.running || (m_background.on && current && m_background.useful &&
                                         m_background.next < p.total && fits);
    if (!m_background.on || !current || p.running || p.done >= p.total)
        return p;
    using Held = BackgroundProgress::Held;
    if (!m_background.useful || m_background.refused) {
        const auto disk = m_dataset->frameCache();
        if (!disk || !disk->enabled())
            p.held = Held::CacheOff;
        else if (m_background.refused || disk->writesRefused())
            p.held = Held::CacheRefusesWrites;
    } else if (m_background.next < p.total && runBytes > 0 && !fits) {
        p.held = Held::RunTooLarge;
        p.runBytes = runBytes;
        p.budgetBytes = budgetBytes;
    }
    return p;
}

bool FramePrefetcher::backgroundFitsLocked(std::uint64_t* runBytes,
                                           std::uint64_t* budgetBytes) const {
    // The run's size at that of the frames in memory (none yet: wait for the views' first).
    const std::size_t cached = m_dataset->cachedFrameCount();
    const auto disk = m_dataset->frameCache();
    if (cached == 0 || !disk)
        return false;
    const double perFrame = double(m_dataset->cachedBytes()) / double(cached);
    const double run = perFrame * double(m_dataset->frameCount());
    const double half = 0.5 * double(disk->settings().budgetBytes);
    if (runBytes)
        *runBytes = static_cast<std::uint64_t>(run);
    if (budgetBytes)
        *budgetBytes = static_cast<std::uint64_t>(half);
    return run <= half;
}

bool FramePrefetcher::backgroundDueLocked() {
    if (!m_background.on || m_background.running || m_stop || !m_queue.empty() ||
        !m_running.empty() || !m_dataset)
        return false;
    if (const std::uint64_t version = m_dataset->strainsVersion();
        !m_background.started || version != m_background.version) {
        m_background.started = true;
        m_background.version = version;
        m_background.next = m_background.done = 0;
        // From the frame a view shows, onwards (then the frames before it): where the user is
        // likely to scrub next is readied first.
        m_background.start = 0;
        for (const auto& [id, channel] : m_channels)
            if (channel.seen) {
                m_background.start = channel.index;
                break;
            }
        m_background.dropped.merge(m_background.bases); // freed by runBackground, unlocked
        m_background.bases.clear();
        m_background.useful = m_dataset->storesDerived(); // once a pass: it stats a file
        m_background.refused = false;
    }
    return m_background.useful && m_background.next < m_dataset->frameCount() &&
           backgroundFitsLocked();
}

bool FramePrefetcher::wantedLocked(std::size_t index) const {
    return std::any_of(m_channels.begin(), m_channels.end(),
                       [&](const auto& c) { return c.second.seen && c.second.index == index; });
}

bool FramePrefetcher::prefetchBehindViewLocked() const {
    return !m_queue.empty() && !wantedLocked(m_queue.front()) &&
           std::any_of(m_running.begin(), m_running.end(),
                       // In memory already (a derived frame being written to the disk cache):
                       // no view waits for it any more.
                       [&](std::size_t r) { return wantedLocked(r) && !m_dataset->isCached(r); });
}

bool FramePrefetcher::nextLoadDueLocked() const {
    return !m_queue.empty() && (!prefetchBehindViewLocked() || m_hold.released);
}

void FramePrefetcher::watchHoldLocked() {
    if (!prefetchBehindViewLocked()) {
        m_hold = {};
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    const double cpu = m_settings.cpuSeconds ? m_settings.cpuSeconds() : processCpuSeconds();
    if (!m_hold.watching) {
        m_hold.watching = true;
        m_hold.since = now;
        m_hold.cpuSeconds = cpu;
        return;
    }
    const double wall = std::chrono::duration<double>(now - m_hold.since).count();
    if (wall < kHoldWindow.count() * 1e-3)
        return;
    // The cores TBB may use, at most those the machine has (tests ask TBB for more threads).
    const double cores = std::max(1u, std::min(unsigned(tbb::this_task_arena::max_concurrency()),
                                               std::max(1u, std::thread::hardware_concurrency())));
    if ((cpu - m_hold.cpuSeconds) / wall < cores - 0.5)
        m_hold.released = true;
    m_hold.since = now;
    m_hold.cpuSeconds = cpu;
}

void FramePrefetcher::runBackground(std::unique_lock<std::mutex>& lock) {
    const std::size_t visit = m_background.next++;
    const std::size_t index = (m_background.start + visit) % m_dataset->frameCount();
    const std::uint64_t version = m_background.version;
    Dataset::BaseFrames bases = std::move(m_background.bases);
    // Frames are freed with the lock released (a request() from the UI must not wait on it).
    Dataset::BaseFrames unused = std::move(m_background.dropped);
    m_background.running = true;
    lock.unlock();
    unused.clear();
    bool stored = false, failed = false;
    try {
        // On one thread: the other core stays for the views' loads (and the UI), and a view's
        // load that arrives meanwhile does not share both with this frame.
        tbb::task_arena one(1);
        one.execute([&] { stored = m_dataset->storeDerivedFrame(index, bases, &m_cancel); });
    } catch (...) {
        // A frame that cannot be read is skipped here: a view that shows it reports the error.
        failed = true;
    }
    lock.lock();
    m_background.running = false;
    const std::size_t count = m_dataset->frameCount();
    if (m_background.version == version && m_dataset->strainsVersion() == version) {
        if (stored)
            ++m_background.done;
        else if (m_cancel) // stopped: done again when the pass goes on
            m_background.next = std::min(m_background.next, visit);
        else if (!failed) { // the cache refused it (the disk short): the rest would be too
            m_background.next = count;
            m_background.refused = true;
        }
        // The references of frames ahead; none after the last frame (the pass goes on from the
        // first then, or is done).
        if (m_background.next < count && index + 1 < count)
            m_background.bases = std::move(bases);
    }
    unused = std::move(bases);  // what was not kept
    auto callback = m_onLoaded; // the UI shows the progress
    ++m_finishing;
    lock.unlock();
    unused.clear();
    if (callback)
        callback(index);
    lock.lock();
    --m_finishing;
}

bool FramePrefetcher::waitIdle(std::chrono::milliseconds timeout) const {
    std::unique_lock lock(m_mutex);
    return m_idle.wait_for(
        lock, timeout, [this] { return m_queue.empty() && m_running.empty() && m_finishing == 0; });
}

std::size_t FramePrefetcher::prefetchDepthLocked() const {
    const std::size_t channels = std::max<std::size_t>(1, m_channels.size());
    const std::size_t cachedCount = m_dataset->cachedFrameCount();
    if (cachedCount == 0) // no idea yet what a frame weighs: one step ahead
        return std::min<std::size_t>(m_settings.lookAhead, 1);
    const std::size_t perFrame = std::max<std::size_t>(1, m_dataset->cachedBytes() / cachedCount);
    const std::size_t fits = m_dataset->cacheBudget() / perFrame;
    // Every channel's current frame stays; what is left is shared among the channels.
    if (fits <= channels)
        return 0;
    return std::min(m_settings.lookAhead, (fits - channels) / channels);
}

std::vector<std::size_t> FramePrefetcher::wishesLocked(const Channel& c, std::size_t depth) const {
    const auto count = static_cast<long long>(m_dataset->frameCount());
    std::vector<std::size_t> wishes{c.index};
    long long at = static_cast<long long>(c.index);
    const long long step = c.direction * static_cast<long long>(c.stride);
    for (std::size_t k = 0; k < depth; ++k) {
        at += step;
        if (at < 0 || at >= count) {
            if (!m_settings.loop)
                break;
            at = ((at % count) + count) % count;
        }
        if (static_cast<std::size_t>(at) == c.index)
            break;
        wishes.push_back(static_cast<std::size_t>(at));
    }
    return wishes;
}

void FramePrefetcher::rebuildQueueLocked() {
    if (m_stop)
        return;
    const std::size_t depth = prefetchDepthLocked();
    std::vector<std::vector<std::size_t>> wishes;
    for (const auto& [id, channel] : m_channels)
        wishes.push_back(wishesLocked(channel, depth));
    // Every channel's own frame first, then the first frame ahead of each, and so on.
    std::deque<std::size_t> queue;
    for (std::size_t rank = 0; rank <= depth; ++rank)
        for (const auto& list : wishes) {
            if (rank >= list.size())
                continue;
            const std::size_t index = list[rank];
            if (m_running.count(index) || m_errors.count(index) ||
                std::find(queue.begin(), queue.end(), index) != queue.end() ||
                m_dataset->isCached(index))
                continue;
            queue.push_back(index);
        }
    m_queue = std::move(queue);
    if (!m_queue.empty())
        m_wake.notify_all();
    else if (m_running.empty() && m_finishing == 0)
        m_idle.notify_all();
}

void FramePrefetcher::work() {
    std::unique_lock lock(m_mutex);
    for (;;) {
        // With a background pass, a look every half second: new strains start it again, and
        // nothing else wakes the workers when no view asks for a frame.
        // A prefetch held back for a view's load: a look every kHoldWindow for an idle core.
        const auto ready = [this] {
            return m_stop || nextLoadDueLocked() || backgroundDueLocked() ||
                   (prefetchBehindViewLocked() && !m_hold.watching);
        };
        watchHoldLocked();
        if (m_hold.watching && !m_hold.released)
            m_wake.wait_for(lock, kHoldWindow, ready);
        else if (m_background.on)
            m_wake.wait_for(lock, std::chrono::milliseconds(500), ready);
        else
            m_wake.wait(lock, ready);
        watchHoldLocked();
        if (m_stop)
            return;
        const bool load = nextLoadDueLocked();
        if (!load && !backgroundDueLocked())
            continue;
        if (!load) {
            runBackground(lock);
            rebuildQueueLocked();
            continue;
        }
        const std::size_t index = m_queue.front();
        m_queue.pop_front();
        m_running.insert(index);
        const auto wake = m_onLoaded;
        lock.unlock();
        std::string error;
        try {
            // The view is woken as soon as the frame is in memory: a frame derived now is then
            // written to the disk cache, which the view need not wait for. (Woken again
            // below, once the load is over: harmless.)
            m_dataset->frame(index, [&] {
                // A prefetch held back for this frame may start. (The lock orders this after
                // a worker's look at the predicate, so the wake is not lost.)
                { std::lock_guard ordered(m_mutex); }
                m_wake.notify_all();
                if (wake)
                    wake(index);
            });
        } catch (const std::exception& e) {
            error = e.what();
        } catch (...) {
            error = "frame " + std::to_string(index) + ": unknown error while loading";
        }
        lock.lock();
        m_running.erase(index);
        if (!error.empty())
            m_errors[index] = std::move(error);
        if (auto callback = m_onLoaded) {
            ++m_finishing; // not idle before the callback has run
            lock.unlock();
            callback(index);
            lock.lock();
            --m_finishing;
        }
        // A frame's weight is known now, and memory may have room for more prefetch.
        rebuildQueueLocked();
    }
}

} // namespace faultline::core
