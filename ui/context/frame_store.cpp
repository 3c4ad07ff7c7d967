#include "ui/context/frame_store.hpp"

#include <chrono>

namespace faultline::ui {

FrameStore::~FrameStore() {
    m_prefetcher.reset();
    m_retiring.clear(); // waits for running loads: fine at exit
}

void FrameStore::retire() {
    std::erase_if(m_retiring, [](const auto& p) { return p->pendingCount() == 0; });
}

void FrameStore::setDataset(std::shared_ptr<core::Dataset> dataset) {
    if (dataset == m_dataset)
        return;
    if (m_prefetcher) {
        m_prefetcher->cancelPending();
        m_retiring.push_back(std::move(m_prefetcher));
    }
    retire();
    m_dataset = std::move(dataset);
    m_waitingFor.reset();
    m_error.clear();
    if (!m_dataset)
        return;
    core::PrefetchSettings settings;
    settings.loop = m_loop;
    m_prefetcher = std::make_unique<core::FramePrefetcher>(m_dataset, settings);
    m_prefetcher->setBackgroundDerivation(true);
    auto wake = m_wake;
    m_prefetcher->setOnLoaded([wake](std::size_t) {
        if (*wake)
            (*wake)();
    });
}

void FrameStore::setLoop(bool loop) {
    if (loop == m_loop)
        return;
    m_loop = loop;
    if (m_prefetcher)
        m_prefetcher->setLoop(loop);
}

void FrameStore::setWakeUp(std::function<void()> wake) { *m_wake = std::move(wake); }

std::shared_ptr<const core::Frame> FrameStore::request(std::size_t index, std::size_t channel) {
    if (!m_retiring.empty())
        retire();
    if (!m_prefetcher || index >= m_dataset->frameCount())
        return nullptr;
    core::FrameRequestResult r = m_prefetcher->request(index, channel);
    switch (r.status) {
    case core::FrameStatus::Ready:
        if (m_waitingFor == index) {
            m_waitingFor.reset();
            m_error.clear();
        }
        return r.frame;
    case core::FrameStatus::Failed:
        m_error = "frame " + std::to_string(index) + ": " + r.error;
        if (m_waitingFor == index)
            m_waitingFor.reset();
        return nullptr;
    case core::FrameStatus::Loading:
        m_waitingFor = index;
        return nullptr;
    }
    return nullptr;
}

bool FrameStore::isLoaded(std::size_t index) const {
    return m_dataset && index < m_dataset->frameCount() && m_dataset->isCached(index);
}

void FrameStore::forgetChannel(std::size_t channel) {
    if (m_prefetcher)
        m_prefetcher->forgetChannel(channel);
}

std::optional<std::size_t> FrameStore::loading() const {
    if (m_waitingFor && !isLoaded(*m_waitingFor))
        return m_waitingFor;
    return std::nullopt;
}

std::string FrameStore::lastError() const { return m_error; }

core::FramePrefetcher::BackgroundProgress FrameStore::backgroundProgress() const {
    return m_prefetcher ? m_prefetcher->backgroundProgress()
                        : core::FramePrefetcher::BackgroundProgress{};
}

void FrameStore::waitIdle() {
    if (m_prefetcher)
        m_prefetcher->waitIdle(std::chrono::minutes(2));
}

} // namespace faultline::ui
