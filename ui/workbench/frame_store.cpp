#include "ui/workbench/frame_store.hpp"

#include <algorithm>
#include <utility>
#include <exception>

namespace faultline::ui {

namespace {
constexpr std::size_t kMaxQueued = 8; // older wishes are dropped while scrubbing
}

FrameStore::FrameStore() : m_worker([this] { run(); }) {}

FrameStore::~FrameStore() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
    }
    m_wakeWorker.notify_all();
    m_worker.join();
}

void FrameStore::setDataset(std::shared_ptr<core::Dataset> dataset) {
    if (dataset == m_dataset)
        return;
    m_dataset = dataset;
    std::lock_guard lock(m_mutex);
    m_workDataset = std::move(dataset);
    m_requests.clear();
    m_prefetches.clear();
    m_failed.clear();
    m_error.clear();
}

void FrameStore::setWakeUp(std::function<void()> wake) {
    std::lock_guard lock(m_mutex);
    m_wake = std::move(wake);
}

std::shared_ptr<const core::Frame> FrameStore::request(std::size_t index) {
    if (!m_dataset || index >= m_dataset->frameCount())
        return nullptr;
    if (auto frame = m_dataset->cachedFrame(index))
        return frame;
    {
        std::lock_guard lock(m_mutex);
        if (std::find(m_failed.begin(), m_failed.end(), index) != m_failed.end())
            return nullptr; // said once in lastError(); not retried until the data changes
        if (m_loading != index) {
            std::erase(m_requests, index);
            m_requests.push_front(index);
            if (m_requests.size() > kMaxQueued)
                m_requests.pop_back();
        }
    }
    m_wakeWorker.notify_one();
    return nullptr;
}

void FrameStore::prefetch(std::size_t index) {
    if (!m_dataset || index >= m_dataset->frameCount() || m_dataset->cachedFrame(index))
        return;
    {
        std::lock_guard lock(m_mutex);
        if (m_loading == index || std::find(m_prefetches.begin(), m_prefetches.end(), index) != m_prefetches.end() ||
            std::find(m_requests.begin(), m_requests.end(), index) != m_requests.end())
            return;
        m_prefetches.push_back(index);
        if (m_prefetches.size() > kMaxQueued)
            m_prefetches.pop_front();
    }
    m_wakeWorker.notify_one();
}

bool FrameStore::isLoaded(std::size_t index) const {
    return m_dataset && index < m_dataset->frameCount() && m_dataset->cachedFrame(index) != nullptr;
}

std::optional<std::size_t> FrameStore::loading() const {
    std::lock_guard lock(m_mutex);
    if (m_loading)
        return m_loading;
    if (!m_requests.empty())
        return m_requests.front();
    return std::nullopt;
}

std::string FrameStore::lastError() const {
    std::lock_guard lock(m_mutex);
    return m_error;
}

bool FrameStore::takeArrivals() {
    std::lock_guard lock(m_mutex);
    return std::exchange(m_arrived, false);
}

void FrameStore::waitIdle() {
    std::unique_lock lock(m_mutex);
    m_idle.wait(lock, [&] { return !m_loading && m_requests.empty() && m_prefetches.empty(); });
}

void FrameStore::run() {
    std::unique_lock lock(m_mutex);
    for (;;) {
        m_wakeWorker.wait(lock, [&] { return m_stop || !m_requests.empty() || !m_prefetches.empty(); });
        if (m_stop)
            return;
        std::deque<std::size_t>& queue = m_requests.empty() ? m_prefetches : m_requests;
        const std::size_t index = queue.front();
        queue.pop_front();
        auto dataset = m_workDataset;
        if (!dataset || index >= dataset->frameCount() ||
            std::find(m_failed.begin(), m_failed.end(), index) != m_failed.end()) {
            if (m_requests.empty() && m_prefetches.empty())
                m_idle.notify_all();
            continue;
        }
        m_loading = index;
        lock.unlock();
        std::string error;
        try {
            dataset->frame(index);
        } catch (const std::exception& e) {
            error = "frame " + std::to_string(index) + ": " + e.what();
        }
        lock.lock();
        m_loading.reset();
        if (dataset == m_workDataset) {
            m_error = error;
            m_arrived = true;
            if (!error.empty())
                m_failed.push_back(index);
        }
        if (m_requests.empty() && m_prefetches.empty())
            m_idle.notify_all();
        if (m_wake) {
            auto wake = m_wake;
            lock.unlock();
            wake();
            lock.lock();
        }
    }
}

} // namespace faultline::ui
