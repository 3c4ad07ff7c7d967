// FaultMetricsCache: each fault's metrics over every frame of the open data, computed in a
// background job (progress, cancel) and kept by the fault's members, so a rename or a colour
// change costs nothing and an edit of the members computes that fault again.
#pragma once

#include "core/data/dataset.hpp"
#include "core/faults/metrics.hpp"
#include "ui/context/jobs.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

namespace faultline::ui {

class FaultMetricsCache {
  public:
    // One fault's metrics, frame by frame (frames[k].frame == k).
    struct Series {
        std::vector<core::FaultFrameMetrics> frames;
        // The first frame in which any member has a broken bond: before it the fault has not
        // formed (issue 41). 0 when no frame counts broken bonds.
        std::size_t formedFrom() const;
    };

    FaultMetricsCache();
    ~FaultMetricsCache();
    FaultMetricsCache(const FaultMetricsCache&) = delete;
    FaultMetricsCache& operator=(const FaultMetricsCache&) = delete;

    // The fault's series for this dataset, or null while it is not computed.
    std::shared_ptr<const Series> find(const std::shared_ptr<core::Dataset>& dataset,
                                       const core::Fault& fault) const;

    // Makes sure the faults' series are there or under way: starts one job for the missing
    // ones (at most one job at a time) and cancels a job whose faults are no longer wanted.
    // Call once per UI frame with the faults on show.
    void request(JobRunner& jobs, double now, const std::shared_ptr<core::Dataset>& dataset,
                 std::span<const core::Fault* const> faults);

    bool computing() const;
    // Of the running job, 0..1; negative when none runs.
    float progress() const;
    // Wall time of the last job that finished, in seconds (0 before the first).
    double lastSeconds() const;
    std::size_t lastFrameCount() const;
    // Why the last job gave nothing: its error, or "cancelled" when the user stopped it
    // (cleared when a job starts). Those faults are not computed again until retry().
    const std::string& lastError() const;
    void retry();

  private:
    struct State; // shared with the job's completion, which may run after a reset
    std::shared_ptr<State> m_state;
};

} // namespace faultline::ui
