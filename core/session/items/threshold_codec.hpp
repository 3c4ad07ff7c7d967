// A variable threshold as JSON: the fields of threshold.add / threshold.set and of a session's
// thresholds[].
#pragma once

#include "core/selection/variable_threshold.hpp"
#include "core/session/items/item_reader.hpp"

namespace faultline::core::items {

Json toJson(const VariableThreshold& threshold);
// Reads the fields present (variable, low, high, enabled).
void patch(VariableThreshold& threshold, const ItemReader& fields);
// The fields, in the table they are declared in once (what threshold.add and threshold.set accept
// besides "index").
std::vector<std::string> thresholdFieldNames();
// A variable; low <= high.
void validate(const VariableThreshold& threshold);

} // namespace faultline::core::items
