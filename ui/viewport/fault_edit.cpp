#include "ui/viewport/fault_edit.hpp"

#include "core/session/commands.hpp"

#include <algorithm>

namespace faultline::ui {

std::string nextFaultName(const core::SessionState& state) {
    for (int k = 1;; ++k) {
        std::string n = "F" + std::to_string(k);
        if (!state.fault(n))
            return n;
    }
}

FaultEdit faultEdit(const core::SessionState& state, const std::set<std::string>& selectedFaults,
                    std::vector<std::int64_t> ids, FaultEditOp op) {
    FaultEdit edit;
    core::normalizeIds(ids);
    if (ids.empty()) {
        edit.message = "No visible sphere there";
        return edit;
    }
    const core::Fault* target =
        selectedFaults.size() == 1 ? state.fault(*selectedFaults.begin()) : nullptr;
    auto plural = [](std::size_t n) {
        return std::to_string(n) + (n == 1 ? " sphere" : " spheres");
    };
    if (op == FaultEditOp::Toggle) {
        op = target && ids.size() == 1 && target->contains(ids[0]) ? FaultEditOp::Remove
                                                                   : FaultEditOp::Add;
    }
    if (op == FaultEditOp::NewFault || (op == FaultEditOp::Add && !target)) {
        const std::string name = nextFaultName(state);
        edit.command = core::cmd::FaultCreate(name, ids);
        edit.selectNext = name;
        edit.message = "New fault " + name + " with " + plural(ids.size());
        return edit;
    }
    if (!target) {
        edit.message = "Select one fault to remove spheres from";
        return edit;
    }
    std::vector<std::int64_t> change;
    for (std::int64_t id : ids)
        if (target->contains(id) == (op == FaultEditOp::Remove))
            change.push_back(id);
    if (change.empty()) {
        edit.message = op == FaultEditOp::Add ? "Those spheres are in " + target->name + " already"
                                              : "None of those spheres is in " + target->name;
        return edit;
    }
    const bool add = op == FaultEditOp::Add;
    edit.command = add ? core::cmd::faultAdd(target->name, change)
                       : core::cmd::faultRemove(target->name, change);
    edit.message = (add ? "Added " : "Removed ") + plural(change.size()) +
                   (add ? " to " : " from ") + target->name;
    return edit;
}

} // namespace faultline::ui
