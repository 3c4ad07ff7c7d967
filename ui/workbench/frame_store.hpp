// FrameStore: frames for the views without ever blocking the UI thread. A frame not in the
// dataset's cache is loaded by one background worker (requests before prefetches, newest
// first); until it arrives the caller keeps showing what it had.
#pragma once

#include "core/model/dataset.hpp"

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace faultline::ui {

class FrameStore {
  public:
    FrameStore();
    ~FrameStore();
    FrameStore(const FrameStore&) = delete;
    FrameStore& operator=(const FrameStore&) = delete;

    // The dataset frames come from; pending loads of another dataset are dropped.
    void setDataset(std::shared_ptr<core::Dataset> dataset);
    const std::shared_ptr<core::Dataset>& dataset() const { return m_dataset; }

    // The frame when it is loaded, else null and a load is queued ahead of other work.
    std::shared_ptr<const core::Frame> request(std::size_t index);
    // Queues a load behind the requests (playback reads ahead in its direction).
    void prefetch(std::size_t index);
    bool isLoaded(std::size_t index) const;

    // The frame being loaded, if any, and the last load error (cleared by the next success).
    std::optional<std::size_t> loading() const;
    std::string lastError() const;
    // True once after a frame arrived (the UI redraws).
    bool takeArrivals();
    // Blocks until nothing is queued or loading (tests, scripted runs).
    void waitIdle();
    void setWakeUp(std::function<void()> wake);

  private:
    void run();

    std::shared_ptr<core::Dataset> m_dataset; // UI thread's view
    mutable std::mutex m_mutex;
    std::condition_variable m_wakeWorker, m_idle;
    std::shared_ptr<core::Dataset> m_workDataset;
    std::deque<std::size_t> m_requests, m_prefetches;
    std::optional<std::size_t> m_loading;
    std::vector<std::size_t> m_failed; // of this dataset
    std::string m_error;
    bool m_arrived = false;
    bool m_stop = false;
    std::function<void()> m_wake;
    std::thread m_worker;
};

} // namespace faultline::ui
