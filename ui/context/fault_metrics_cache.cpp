#include "ui/context/fault_metrics_cache.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <set>
#include <stdexcept>

namespace faultline::ui {

struct FaultMetricsCache::State {
    std::shared_ptr<core::Dataset> dataset; // the series below belong to this one
    std::map<std::uint64_t, std::shared_ptr<const Series>> series;
    std::shared_ptr<Job> job;
    std::set<std::uint64_t> jobKeys;
    double lastSeconds = 0;
    std::size_t lastFrames = 0;
    std::string lastError;
    std::set<std::uint64_t> failedKeys; // not started again for this dataset
};

FaultMetricsCache::FaultMetricsCache() : m_state(std::make_shared<State>()) {}

FaultMetricsCache::~FaultMetricsCache() {
    if (m_state->job)
        m_state->job->cancel();
}

std::size_t FaultMetricsCache::Series::formedFrom() const {
    const auto it = std::find_if(frames.begin(), frames.end(),
                                 [](const core::FaultFrameMetrics& m) { return m.broken > 0; });
    return it == frames.end() ? 0 : static_cast<std::size_t>(it - frames.begin());
}

// A fault's series is kept under core::hashMemberIds of its members (not its name, colour or
// notes).
std::shared_ptr<const FaultMetricsCache::Series>
FaultMetricsCache::find(const std::shared_ptr<core::Dataset>& dataset,
                        const core::Fault& fault) const {
    if (!dataset || dataset != m_state->dataset)
        return nullptr;
    auto it = m_state->series.find(core::hashMemberIds(fault.ids));
    return it == m_state->series.end() ? nullptr : it->second;
}

// The job is dropped by its completion (or when cancelled), so a finished job whose result has
// not been handed over yet still counts: no second job starts for the same faults.
bool FaultMetricsCache::computing() const { return m_state->job != nullptr; }

float FaultMetricsCache::progress() const {
    return computing() ? std::max(0.0f, m_state->job->progress()) : -1.0f;
}

double FaultMetricsCache::lastSeconds() const { return m_state->lastSeconds; }
std::size_t FaultMetricsCache::lastFrameCount() const { return m_state->lastFrames; }
const std::string& FaultMetricsCache::lastError() const { return m_state->lastError; }

void FaultMetricsCache::retry() {
    m_state->failedKeys.clear();
    m_state->lastError.clear();
}

void FaultMetricsCache::request(JobRunner& jobs, double now,
                                const std::shared_ptr<core::Dataset>& dataset,
                                std::span<const core::Fault* const> faults) {
    State& s = *m_state;
    if (dataset != s.dataset) {
        if (s.job)
            s.job->cancel();
        s.job.reset();
        s.jobKeys.clear();
        s.series.clear();
        s.failedKeys.clear();
        s.dataset = dataset;
    }
    if (s.job && s.job->cancelRequested()) {
        // Cancelled from the status bar: not started again until retry().
        s.lastError = "cancelled";
        s.failedKeys.insert(s.jobKeys.begin(), s.jobKeys.end());
        s.job.reset();
        s.jobKeys.clear();
    }
    if (!dataset || dataset->frameCount() == 0)
        return;
    std::vector<core::Fault> missing;
    std::set<std::uint64_t> wanted, missingKeys;
    for (const core::Fault* f : faults) {
        const std::uint64_t key = core::hashMemberIds(f->ids);
        wanted.insert(key);
        if (!s.series.count(key) && !s.failedKeys.count(key) && missingKeys.insert(key).second)
            missing.push_back(*f);
    }
    if (s.job) {
        const bool stillWanted = std::any_of(s.jobKeys.begin(), s.jobKeys.end(),
                                             [&](auto k) { return wanted.count(k) > 0; });
        if (stillWanted)
            return; // one job at a time; the rest follow when it is done
        s.job->cancel();
        s.job.reset();
        s.jobKeys.clear();
    }
    if (missing.empty())
        return;

    std::vector<std::uint64_t> keys;
    for (const auto& f : missing)
        keys.push_back(core::hashMemberIds(f.ids));
    s.jobKeys = std::set<std::uint64_t>(keys.begin(), keys.end());
    s.lastError.clear();
    std::weak_ptr<State> weak = m_state;
    const std::string title =
        missing.size() == 1
            ? "Metrics of " + missing.front().name + " over all frames"
            : "Metrics of " + std::to_string(missing.size()) + " faults over all frames";
    s.job = jobs.start(
        title,
        [dataset, faults = std::move(missing), keys,
         weak](JobControl& control) -> std::function<void()> {
            const auto start = std::chrono::steady_clock::now();
            const std::size_t n = dataset->frameCount();
            std::atomic<std::size_t> done{0};
            control.setProgress(0.0f);
            auto load = [&](std::size_t k) {
                if (control.cancelled())
                    throw std::runtime_error("cancelled");
                auto frame = dataset->frame(k);
                control.setProgress(static_cast<float>(++done) / static_cast<float>(n));
                return frame;
            };
            auto series = std::make_shared<core::FaultMetricsSeries>(
                core::computeMetricsSeries(n, load, faults));
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return [weak, dataset, series, keys, seconds] {
                auto state = weak.lock();
                if (!state || state->dataset != dataset)
                    return;
                for (std::size_t k = 0; k < keys.size(); ++k) {
                    auto one = std::make_shared<Series>();
                    one->frames.reserve(series->frameCount);
                    for (std::size_t f = 0; f < series->frameCount; ++f)
                        one->frames.push_back(series->at(f, k));
                    state->series[keys[k]] = std::move(one);
                }
                state->lastSeconds = seconds;
                state->lastFrames = series->frameCount;
                state->job.reset();
                state->jobKeys.clear();
            };
        },
        [weak, keys](const std::string& error) {
            if (auto state = weak.lock()) {
                state->lastError = error;
                state->failedKeys.insert(keys.begin(), keys.end());
                state->job.reset();
                state->jobKeys.clear();
            }
        },
        now);
}

} // namespace faultline::ui
