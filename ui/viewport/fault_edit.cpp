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

core::Json withEmptiedRemoved(const core::SessionState& state, core::Json command,
                              std::vector<std::int64_t> ids, const std::string& into,
                              std::vector<std::string>* emptied) {
    core::normalizeIds(ids);
    std::vector<core::Json> batch{std::move(command)};
    for (const core::Fault& f : state.faults) {
        if (f.name == into || f.ids.empty())
            continue;
        const bool all = std::all_of(f.ids.begin(), f.ids.end(), [&](std::int64_t id) {
            return std::binary_search(ids.begin(), ids.end(), id);
        });
        if (!all)
            continue;
        batch.push_back(core::cmd::faultDelete(f.name));
        if (emptied)
            emptied->push_back(f.name);
    }
    return core::cmd::batch(std::move(batch));
}

namespace {
// "; C2 emptied and deleted" for the status line, or nothing.
std::string emptiedNote(const std::vector<std::string>& emptied) {
    if (emptied.empty())
        return {};
    std::string names;
    for (const auto& n : emptied)
        names += (names.empty() ? "" : ", ") + n;
    return "; " + names + (emptied.size() == 1 ? " was" : " were") + " left empty and deleted";
}
} // namespace

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
        std::vector<std::string> emptied;
        edit.command =
            withEmptiedRemoved(state, core::cmd::FaultCreate(name, ids), ids, name, &emptied);
        edit.selectNext = name;
        edit.message = "New fault " + name + " with " + plural(ids.size()) + emptiedNote(emptied);
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
    std::vector<std::string> emptied;
    edit.command = add ? withEmptiedRemoved(state, core::cmd::faultAdd(target->name, change),
                                            change, target->name, &emptied)
                       : core::cmd::faultRemove(target->name, change);
    edit.message = (add ? "Added " : "Removed ") + plural(change.size()) +
                   (add ? " to " : " from ") + target->name + emptiedNote(emptied);
    return edit;
}

} // namespace faultline::ui
