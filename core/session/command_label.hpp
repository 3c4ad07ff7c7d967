// What a command does, in words a user reads in Edit > Undo and the status line
// ("add 279 spheres to F1", "change the strain threshold").
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace faultline::core {

// A short lower-case phrase for a state-changing command; the op's name for ops it does not know
// and for malformed commands (it never throws). spheresChanged: how many spheres a fault.add or
// fault.remove moved (which "from":"visible" does not say), when the caller knows.
std::string describeCommand(const nlohmann::json& cmd, long long spheresChanged = -1);

// A command's error in the same words: "threshold.set: low must not exceed high" becomes
// "Could not change the strain threshold: low must not exceed high"; "Nothing to undo".
std::string describeFailure(const nlohmann::json& cmd, const std::string& message);

} // namespace faultline::core
