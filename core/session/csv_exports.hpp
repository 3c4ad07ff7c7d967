// The text export.csv writes, as a pure function of a session state and its data: the op runs it
// in place, the workbench on a worker thread with a copy of the state (tracks and metrics read
// every frame, far more than a UI frame may take).
#pragma once

#include "core/data/dataset.hpp"
#include "core/faults/frame_loader.hpp"
#include "core/session/command_args.hpp"
#include "core/session/session_state.hpp"

#include <functional>
#include <memory>
#include <string>

namespace faultline::core {

// cmd: {"what": faults | fault_metrics | fault_tracks | fault_events, candidate options (tracks,
// events: "method", "link", "min_size", "angle", "radius")}; the other
// fields are not looked at. Rows over time only for the selected frames (replay --frames,
// --shard). Throws CommandError (what is wrong, or that data is needed).
// `beforeFrame`, when given, runs before each frame is read (it may throw to stop the export:
// the Python module's Ctrl+C).
std::string exportCsvText(const SessionState& state, const std::shared_ptr<Dataset>& data,
                          const Json& cmd, const FrameSelection& frames = {},
                          const std::function<void()>& beforeFrame = {});

} // namespace faultline::core
