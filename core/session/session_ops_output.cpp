// Actions that write files: session.save, export.*, and the contract's ops whose features have
// not landed yet (a clear error instead of a silent pass).
#include "core/session/session_ops.hpp"

#include "core/faults/fault_export.hpp"
#include "core/faults/metrics.hpp"
#include "core/faults/tracking.hpp"
#include "core/selection/column_view.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/atomic_file.hpp"
#include "core/session/csv_exports.hpp"

#include <algorithm>
#include <cstdio>

namespace faultline::core {

namespace {

// The visible mask of a frame as the session's boxes, thresholds and fault filter say.
VisibleMaskFn sessionVisibleMask(const SessionState& st) {
    return [&st](const Frame& frame, std::size_t) {
        const auto rowMask = Session::faultRowMask(st, frame);
        return computeVisibility(frame, st.boxes, st.thresholds, rowMask.get()).mask;
    };
}

// Each fault's membership through time: per frame, the candidate of the visible spheres that
// shares most ids with it.
std::vector<FaultTrack> trackedFaults(const SessionState& st, const std::shared_ptr<Dataset>& ds,
                                      const CandidateOptions& options,
                                      const FrameSelection& frames) {
    if (!ds)
        throw CommandError("export.csv: fault_tracks needs open data");
    return trackFaults(
        ds->frameCount(), [ds](std::size_t k) { return ds->frame(k); }, sessionVisibleMask(st),
        st.faults, options, false, frames);
}

// what = spheres: "id,<variables>", a row per sphere of the current frame (or its visible ones).
std::string spheresCsv(const SessionState& st, const std::shared_ptr<Dataset>& ds,
                       const Json& cmd) {
    if (!ds)
        throw CommandError("export.csv: spheres needs open data");
    const auto frame = ds->frame(std::min(st.frame, ds->frameCount() - 1));
    // Default: every variable, positions and radius first.
    std::vector<std::string> names = {"x", "y", "z", "radius"};
    if (cmd.contains("variables"))
        names = args::strings(cmd, "variables");
    else
        for (const auto& n : variableNamesOf(*frame))
            if (std::find(names.begin(), names.end(), n) == names.end())
                names.push_back(n);
    const bool onlyVisible = args::optionalBool(cmd, "only_visible").value_or(false);
    std::vector<ColumnView> columns;
    for (const auto& n : names) {
        const auto column = findColumn(*frame, n);
        if (!column)
            throw CommandError("export.csv: " + missingVariableNote(*frame, n) + " (frame " +
                               std::to_string(st.frame) + ")");
        columns.push_back(*column);
    }
    std::vector<std::uint8_t> mask;
    if (onlyVisible) {
        const auto rowMask = Session::faultRowMask(st, *frame);
        mask = computeVisibility(*frame, st.boxes, st.thresholds, rowMask.get()).mask;
    }
    std::string out = "id";
    for (const auto& n : names)
        out += "," + n;
    out += "\n";
    char buf[32];
    for (std::size_t row = 0; row < frame->size(); ++row) {
        if (onlyVisible && !mask[row])
            continue;
        out += std::to_string(frame->ids[row]);
        for (const ColumnView& c : columns) {
            if (c.isInteger()) {
                out += ',';
                out += std::to_string(c.ints[row]);
            } else {
                std::snprintf(buf, sizeof buf, ",%.9g", static_cast<double>(c.floats[row]));
                out += buf;
            }
        }
        out += '\n';
    }
    return out;
}

} // namespace

std::string exportCsvText(const SessionState& state, const std::shared_ptr<Dataset>& ds,
                          const Json& cmd, const FrameSelection& frames,
                          const std::function<void()>& beforeFrame) {
    const std::string what = args::string(cmd, "what");
    if (what == "faults")
        return faultsCsv(state.faults);
    if (what == "spheres")
        return spheresCsv(state, ds, cmd);
    if (what != "fault_metrics" && what != "fault_tracks" && what != "fault_growth" &&
        what != "fault_events")
        throw CommandError("export.csv: \"what\" must be faults, spheres, fault_metrics, "
                           "fault_growth, fault_tracks or fault_events");
    if (!ds)
        throw CommandError("export.csv: " + what + " needs open data");
    const FrameLoader load = [ds, &beforeFrame](std::size_t k) {
        if (beforeFrame)
            beforeFrame();
        return ds->frame(k);
    };
    if (what == "fault_metrics")
        return faultMetricsCsv(
            computeMetricsSeries(ds->frameCount(), load, state.faults, {}, frames));
    const CandidateOptions options = detail::candidateOptionsFrom(cmd, "export.csv");
    if (what == "fault_tracks")
        return faultTracksCsv(state.faults, trackedFaults(state, ds, options, frames));
    if (what == "fault_growth")
        return faultMetricsCsv(trackedMetricsSeries(ds->frameCount(), load,
                                                    sessionVisibleMask(state), state.faults,
                                                    options, {}, nullptr, frames));
    return faultEventsCsv(state.faults,
                          trackedFaultEvents(ds->frameCount(), load, sessionVisibleMask(state),
                                             state.faults, options, frames));
}

} // namespace faultline::core

namespace faultline::core::detail {

void registerOutputOps(OpRegistry& ops) {
    addAction(ops, "session.save", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"path"});
        const std::string path = s.outputPath(args::string(cmd, "path"));
        try {
            saveSessionFile(s.state(), path);
        } catch (const std::exception& e) {
            throw CommandError(std::string("session.save: ") + e.what());
        }
        s.markSaved();
        return nullptr;
    });
    addAction(ops, "export.csv", [](Session& s, const Json& cmd) -> Json {
        // what = faults: "id,fault", a row per member; fault_metrics: a row per frame and fault;
        // fault_growth: the fault_metrics columns on what each fault is in each frame (its
        // matching candidate); fault_tracks: per frame and fault, the candidate that matches it
        // best; fault_events:
        // when tracked faults appeared, linked and split (candidate options as
        // fault.candidates: "method", "link", "min_size", "angle", "radius").
        args::onlyFields(cmd, {"what", "path", "link", "min_size", "method", "angle", "radius",
                               "variables", "only_visible"});
        const std::string path = s.outputPath(args::string(cmd, "path"));
        const std::string text = exportCsvText(s.state(), s.dataset(), cmd, s.frameSelection(),
                                               [&s] { s.throwIfInterrupted("export.csv"); });
        try {
            writeFileAtomically(path, text);
        } catch (const std::exception& e) {
            throw CommandError(std::string("export.csv: ") + e.what());
        }
        return nullptr;
    });
    addNotYet(ops, "render",
              "rendering needs the renderer; run `faultline replay` from a build with the GUI");
}

} // namespace faultline::core::detail
