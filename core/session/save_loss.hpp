// What writing a session over a session file would lose: the file's data, faults, fault members,
// boxes and thresholds that the state to save does not hold. The workbench asks before such a
// save (issue 41: an emptied session once overwrote a 123 KB analysis without a word).
#pragma once

#include "core/session/session_state.hpp"

#include <string>
#include <vector>

namespace faultline::core {

// One phrase per kind of loss ("fault F3 (1,204 spheres)", "the data (dump.gz)", "2 boxes");
// empty when `next` holds everything `onDisk` does (it may hold more, or other values).
std::vector<std::string> saveLoss(const SessionState& onDisk, const SessionState& next);

// The same against the file at `path`: empty when there is no file there; one phrase saying so
// when the file exists but is not a session this build can read (it would be replaced).
std::vector<std::string> saveLossOverFile(const std::string& path, const SessionState& next);

} // namespace faultline::core
