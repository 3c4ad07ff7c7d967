// FrameStore: frames for the views without ever blocking the UI thread, on the core's
// FramePrefetcher (loads on worker threads, the next frames prefetched in each view's direction
// of travel within the dataset's memory budget). Until a frame arrives the caller keeps showing
// what it had.
#pragma once

#include "core/data/dataset.hpp"
#include "core/data/frame_prefetcher.hpp"

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

class FrameStore {
  public:
    FrameStore() = default;
    ~FrameStore();
    FrameStore(const FrameStore&) = delete;
    FrameStore& operator=(const FrameStore&) = delete;

    // The dataset frames come from; pending loads of another dataset are dropped.
    void setDataset(std::shared_ptr<core::Dataset> dataset);
    const std::shared_ptr<core::Dataset>& dataset() const { return m_dataset; }
    void setLoop(bool loop);

    // The frame when it is in memory, else null and it is loaded ahead of any prefetch.
    // `channel`: one per view (its requests give the direction to read ahead in).
    std::shared_ptr<const core::Frame> request(std::size_t index, std::size_t channel = 0);
    bool isLoaded(std::size_t index) const;
    void forgetChannel(std::size_t channel);

    // A frame asked for and not there yet, if any; the last load error (cleared by a success).
    std::optional<std::size_t> loading() const;
    std::string lastError() const;
    // The pass that derives every frame's strain into the disk cache while the views are idle
    // (FramePrefetcher::setBackgroundDerivation, on for the workbench's dataset).
    core::FramePrefetcher::BackgroundProgress backgroundProgress() const;
    // Blocks until nothing is queued or loading (tests, scripted runs).
    void waitIdle();
    // Called on a worker thread after each load (wakes an idle event loop).
    void setWakeUp(std::function<void()> wake);

  private:
    std::shared_ptr<core::Dataset> m_dataset;
    std::unique_ptr<core::FramePrefetcher> m_prefetcher;
    // Prefetchers of datasets no longer shown, kept until their running load ends (a reader
    // cannot be interrupted, and waiting for it would freeze the UI).
    std::vector<std::unique_ptr<core::FramePrefetcher>> m_retiring;
    void retire();
    bool m_loop = false;
    std::optional<std::size_t> m_waitingFor;
    std::string m_error;
    std::shared_ptr<std::function<void()>> m_wake = std::make_shared<std::function<void()>>();
};

} // namespace faultline::ui
