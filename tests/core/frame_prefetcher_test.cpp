#include "core/data/frame_prefetcher.hpp"
#include "core/io/input_error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <future>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

using namespace faultline::core;
using namespace std::chrono_literals;

namespace {

// A synthetic dataset whose loads are recorded in order, and can be held back or made to fail.
class RecordingLoader {
  public:
    explicit RecordingLoader(std::size_t frames, std::size_t particles = 1000)
        : m_dataset(Dataset::fromLoader(frames,
                                        [this, particles](std::size_t k) {
                                            {
                                                std::lock_guard lock(m_mutex);
                                                m_started.push_back(k);
                                            }
                                            m_gate.wait();
                                            {
                                                std::lock_guard lock(m_mutex);
                                                m_loaded.push_back(k);
                                            }
                                            if (m_failing.count(k))
                                                throw InputError("run/dump." + std::to_string(k),
                                                                 InputError::Where::Line, 7,
                                                                 "expected a number");
                                            Frame f;
                                            f.timestep = static_cast<std::int64_t>(k) * 100;
                                            for (std::size_t i = 0; i < particles; ++i) {
                                                f.ids.push_back(static_cast<std::int64_t>(i));
                                                f.x.push_back(float(k));
                                                f.y.push_back(0);
                                                f.z.push_back(0);
                                                f.radius.push_back(0.5f);
                                            }
                                            f.finalize();
                                            return f;
                                        })),
          m_gate(m_open.get_future().share()) {}

    void holdLoads() { m_gate = (m_held = std::promise<void>()).get_future().share(); }
    void releaseLoads() { m_held.set_value(); }
    void failOn(std::size_t k) { m_failing.insert(k); }
    std::vector<std::size_t> loaded() const {
        std::lock_guard lock(m_mutex);
        return m_loaded;
    }
    // Loads begun, held back or not, in the order they began.
    std::vector<std::size_t> started() const {
        std::lock_guard lock(m_mutex);
        return m_started;
    }
    void forgetLoaded() {
        std::lock_guard lock(m_mutex);
        m_loaded.clear();
        m_started.clear();
    }
    std::shared_ptr<Dataset> dataset() const { return m_dataset; }

  private:
    std::shared_ptr<Dataset> m_dataset;
    std::promise<void> m_open = [] {
        std::promise<void> p;
        p.set_value();
        return p;
    }();
    std::promise<void> m_held;
    std::shared_future<void> m_gate;
    std::set<std::size_t> m_failing;
    mutable std::mutex m_mutex;
    std::vector<std::size_t> m_loaded, m_started;
};

PrefetchSettings oneWorker(std::size_t lookAhead) {
    PrefetchSettings s;
    s.workers = 1;
    s.lookAhead = lookAhead;
    return s;
}

} // namespace

TEST(FramePrefetcher, DeliversTheRequestedFrame) {
    RecordingLoader loader(5);
    FramePrefetcher p(loader.dataset());
    FrameRequestResult r = p.request(2);
    EXPECT_NE(r.status, FrameStatus::Failed);
    ASSERT_TRUE(p.waitIdle(10s));
    r = p.request(2);
    ASSERT_EQ(r.status, FrameStatus::Ready);
    EXPECT_EQ(r.frame->timestep, 200);
    EXPECT_EQ(p.peek(2).frame, r.frame);
    EXPECT_EQ(p.request(9).status, FrameStatus::Failed); // out of range: an error, not a throw
}

TEST(FramePrefetcher, RequestNeverWaitsForALoad) {
    RecordingLoader loader(5);
    loader.holdLoads(); // every load now waits until released
    FramePrefetcher p(loader.dataset());
    // Were request() to wait for the load, it would never return while loads are held.
    auto asked = std::async(std::launch::async, [&] { return p.request(3).status; });
    ASSERT_EQ(asked.wait_for(30s), std::future_status::ready);
    EXPECT_EQ(asked.get(), FrameStatus::Loading);
    EXPECT_EQ(p.request(3).status, FrameStatus::Loading);
    EXPECT_GE(p.pendingCount(), 1u);
    loader.releaseLoads();
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(p.request(3).status, FrameStatus::Ready);
}

TEST(FramePrefetcher, PrefetchesInTheDirectionOfTravel) {
    RecordingLoader loader(20);
    FramePrefetcher p(loader.dataset(), oneWorker(3));
    p.request(10);
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{10, 11, 12, 13})); // forward at first
    loader.forgetLoaded();
    p.request(9); // one step back: backwards from here on
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{9, 8, 7, 6}));
    loader.forgetLoaded();
    p.request(7); // in memory already; two steps back: prefetch with that stride
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{5, 3, 1}));
    loader.forgetLoaded();
    p.request(1);
    p.request(0); // no frame before 0 without loop
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{0}));
}

TEST(FramePrefetcher, LoopWrapsAroundTheEnds) {
    RecordingLoader loader(6);
    PrefetchSettings s = oneWorker(2);
    s.loop = true;
    FramePrefetcher p(loader.dataset(), s);
    p.request(4);
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{4, 5, 0}));
    loader.forgetLoaded();
    p.request(5);
    p.request(0); // playing on past the end: still forward
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{1, 2}));
}

TEST(FramePrefetcher, PrefetchStaysWithinTheMemoryBudget) {
    RecordingLoader loader(30);
    loader.dataset()->frame(0); // learn what a frame weighs
    const std::size_t perFrame = loader.dataset()->cachedBytes();
    loader.dataset()->setCacheBudget(perFrame * 4); // the current frame and three more
    loader.forgetLoaded();
    FramePrefetcher p(loader.dataset(), oneWorker(10));
    p.request(10);
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded(), (std::vector<std::size_t>{10, 11, 12, 13}));
    EXPECT_LE(loader.dataset()->cachedBytes(), perFrame * 4);
}

TEST(FramePrefetcher, ChannelsAreServedCurrentFramesFirst) {
    RecordingLoader loader(30);
    loader.holdLoads();
    FramePrefetcher p(loader.dataset(), oneWorker(2));
    p.request(20, 0);
    p.request(5, 1);
    loader.releaseLoads();
    ASSERT_TRUE(p.waitIdle(10s));
    const auto order = loader.loaded();
    ASSERT_GE(order.size(), 2u);
    EXPECT_EQ(order[0], 20u);
    EXPECT_EQ(order[1], 5u); // before any prefetch of channel 0
    EXPECT_EQ(p.request(20, 0).status, FrameStatus::Ready);
    EXPECT_EQ(p.request(5, 1).status, FrameStatus::Ready);
}

// On 2 cores a prefetch beside the frame a view waits for made that frame take twice as long:
// prefetches wait while it loads on every core. Frames that views show now load side by side.
TEST(FramePrefetcher, PrefetchesWaitForTheFrameAViewWaitsFor) {
    RecordingLoader loader(20);
    loader.dataset()->frame(0); // a frame's weight is known: three ahead from the start
    loader.forgetLoaded();
    loader.holdLoads();
    PrefetchSettings settings;
    settings.workers = 2;
    settings.lookAhead = 3;
    const auto start = std::chrono::steady_clock::now();
    settings.cpuSeconds = [start] { // every core busy, however many there are
        return 1000 *
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    FramePrefetcher p(loader.dataset(), settings);
    p.request(10);
    std::this_thread::sleep_for(200ms); // time for an idle worker to start a prefetch
    EXPECT_EQ(loader.started(), (std::vector<std::size_t>{10}));
    p.request(4, 1); // another view's frame: loads now, beside frame 10
    for (int k = 0; k < 10000 && loader.started().size() < 2; ++k)
        std::this_thread::sleep_for(1ms);
    EXPECT_EQ(loader.started(), (std::vector<std::size_t>{10, 4}));
    loader.releaseLoads();
    ASSERT_TRUE(p.waitIdle(10s));
    auto loaded = loader.loaded();
    std::sort(loaded.begin(), loaded.end());
    EXPECT_EQ(loaded, (std::vector<std::size_t>{4, 5, 6, 7, 10, 11, 12, 13}));
}

// A view's load that leaves a core idle (a gzip file inflates on one thread) does not hold the
// prefetch back: it starts on that core.
TEST(FramePrefetcher, PrefetchesUseACoreTheViewsLoadLeavesIdle) {
    RecordingLoader loader(20);
    loader.dataset()->frame(0);
    loader.forgetLoaded();
    loader.holdLoads();
    PrefetchSettings settings;
    settings.workers = 2;
    settings.lookAhead = 3;
    settings.cpuSeconds = [] { return 0.0; }; // nothing busy
    FramePrefetcher p(loader.dataset(), settings);
    p.request(10);
    for (int k = 0; k < 10000 && loader.started().size() < 2; ++k)
        std::this_thread::sleep_for(1ms);
    EXPECT_EQ(loader.started(), (std::vector<std::size_t>{10, 11}));
    loader.releaseLoads();
    ASSERT_TRUE(p.waitIdle(10s));
}

TEST(FramePrefetcher, LoadErrorsAreValuesUntilRetried) {
    RecordingLoader loader(5);
    loader.failOn(3);
    FramePrefetcher p(loader.dataset(), oneWorker(0));
    std::size_t callbacks = 0;
    std::mutex m;
    p.setOnLoaded([&](std::size_t) {
        std::lock_guard lock(m);
        ++callbacks;
    });
    p.request(3);
    ASSERT_TRUE(p.waitIdle(10s));
    FrameRequestResult r = p.request(3);
    ASSERT_EQ(r.status, FrameStatus::Failed);
    EXPECT_EQ(r.error, "run/dump.3:7: expected a number");
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded().size(), 1u); // a failed frame is not retried by itself
    p.retry(3);
    EXPECT_EQ(p.request(3).status, FrameStatus::Loading);
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_EQ(loader.loaded().size(), 2u);
    std::lock_guard lock(m);
    EXPECT_EQ(callbacks, 2u);
}

TEST(FramePrefetcher, CancelDropsQueuedLoads) {
    RecordingLoader loader(30);
    loader.holdLoads();
    FramePrefetcher p(loader.dataset(), oneWorker(5));
    p.request(0);
    p.request(1);
    p.request(2); // 0 is running; the rest queued
    p.cancelPending();
    loader.releaseLoads();
    ASSERT_TRUE(p.waitIdle(10s));
    EXPECT_LE(loader.loaded().size(), 1u); // only what was already running
}

TEST(FramePrefetcher, DestroyingWhileLoadsRunIsSafe) {
    RecordingLoader loader(30);
    loader.holdLoads();
    auto p = std::make_unique<FramePrefetcher>(loader.dataset());
    p->request(4);
    p->request(5);
    auto done = std::async(std::launch::async, [&] { p.reset(); });
    loader.releaseLoads();
    ASSERT_EQ(done.wait_for(30s), std::future_status::ready);
}
