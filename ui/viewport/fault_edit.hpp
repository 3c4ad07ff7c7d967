// What picking spheres in a view does to the faults: the one journal command (fault.create,
// fault.add or fault.remove with "ids") for a set of picked ids, given the selected fault.
// Shared by the viewport's click and rectangle/lasso selection and the Faults panel's names.
#pragma once

#include "core/session/command_args.hpp"
#include "core/session/session_state.hpp"

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace faultline::ui {

enum class FaultEditOp {
    Add,      // into the selected fault (a new fault when not exactly one is selected)
    Remove,   // from the selected fault
    NewFault, // always a new fault
    Toggle,   // one sphere: out of the selected fault when a member, else in (as Add)
};

struct FaultEdit {
    core::Json command;     // null when there is nothing to do
    std::string selectNext; // the fault to select once applied (a new fault), else empty
    std::string message;    // why nothing happens, or what did
};

// The first free name F1, F2, ...
std::string nextFaultName(const core::SessionState& state);

// `command` (one that puts `ids` into a fault: fault.create, fault.add, fault.candidates),
// followed by deleting the other faults it leaves with no sphere, as one undo step. The ops
// themselves keep an emptied fault (journals count on it), and an empty fault left in the list,
// the legend and the metrics confused users (walkthrough of issue 41). `into`: the fault the
// spheres go to (not deleted); `emptied`, when given, receives the deleted faults' names.
core::Json withEmptiedRemoved(const core::SessionState& state, core::Json command,
                              std::vector<std::int64_t> ids, const std::string& into,
                              std::vector<std::string>* emptied = nullptr);

// `ids` are the picked spheres (any order). Adding sends only the ids not yet members and
// removing only members, so the journal holds what changed; a fault the spheres leave empty is
// deleted in the same step (withEmptiedRemoved).
FaultEdit faultEdit(const core::SessionState& state, const std::set<std::string>& selectedFaults,
                    std::vector<std::int64_t> ids, FaultEditOp op);

} // namespace faultline::ui
