// Ops on what is selected: box.add/set/remove, threshold.add/set/remove (JOURNAL.md).
#include "core/session/session_ops.hpp"

#include "core/session/items/item_codecs.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::core::detail {

namespace {

template <typename T> std::size_t indexArg(const Json& cmd, const std::vector<T>& items) {
    const long long i =
        args::optionalInteger(cmd, "index").value_or(static_cast<long long>(items.size()));
    return static_cast<std::size_t>(std::clamp(i, 0LL, static_cast<long long>(items.size())));
}

// The items' fields, from their codecs' tables.
const std::vector<std::string>& boxFields() {
    static const std::vector<std::string> fields = items::boxFieldNames();
    return fields;
}
const std::vector<std::string>& thresholdFields() {
    static const std::vector<std::string> fields = items::thresholdFieldNames();
    return fields;
}

} // namespace

void registerSelectionOps(OpRegistry& ops) {
    addStateOp(ops, "box.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"index"}, boxFields());
        const std::string name = args::string(cmd, "name");
        if (name.empty() || s.state().box(name))
            throw CommandError("box.add: a box named \"" + name + "\" exists already");
        const CuttingBox b = items::patched("box.add", CuttingBox{}, cmd, {"name", "min", "max"});
        auto& boxes = s.mutableState().boxes;
        boxes.insert(boxes.begin() + static_cast<long>(indexArg(cmd, boxes)), b);
        return {{"op", "box.remove"}, {"name", b.name}};
    });
    addStateOp(ops, "box.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"rename"}, boxFields());
        const std::string name = args::string(cmd, "name");
        CuttingBox* b = s.mutableState().box(name);
        if (!b)
            throw CommandError("box.set: no box named \"" + name + "\"");
        CuttingBox next = items::patched("box.set", *b, cmd);
        if (auto rename = args::optionalString(cmd, "rename")) {
            if (rename->empty() || (*rename != name && s.state().box(*rename)))
                throw CommandError("box.set: cannot rename to \"" + *rename + "\"");
            next.name = *rename;
        }
        Json inverse = items::toJson(*b);
        inverse.erase("name");
        inverse["op"] = "box.set";
        inverse["name"] = next.name;
        if (next.name != name)
            inverse["rename"] = name;
        *b = next;
        return inverse;
    });
    addStateOp(ops, "box.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name"});
        const std::string name = args::string(cmd, "name");
        auto& boxes = s.mutableState().boxes;
        auto it = std::find_if(boxes.begin(), boxes.end(),
                               [&](const CuttingBox& b) { return b.name == name; });
        if (it == boxes.end())
            throw CommandError("box.remove: no box named \"" + name + "\"");
        Json inverse = items::toJson(*it);
        inverse["op"] = "box.add";
        inverse["index"] = it - boxes.begin();
        boxes.erase(it);
        return inverse;
    });

    addStateOp(ops, "threshold.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"index"}, thresholdFields());
        const std::string variable = args::string(cmd, "variable");
        if (variable.empty() || s.state().threshold(variable))
            throw CommandError("threshold.add: \"" + variable +
                               "\" has a threshold already (use threshold.set)");
        const VariableThreshold t = items::patched("threshold.add", VariableThreshold{}, cmd);
        auto& list = s.mutableState().thresholds;
        list.insert(list.begin() + static_cast<long>(indexArg(cmd, list)), t);
        return {{"op", "threshold.remove"}, {"variable", t.variable}};
    });
    addStateOp(ops, "threshold.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {}, thresholdFields());
        const std::string variable = args::string(cmd, "variable");
        VariableThreshold* t = s.mutableState().threshold(variable);
        if (!t)
            throw CommandError("threshold.set: no threshold on \"" + variable + "\"");
        const VariableThreshold next = items::patched("threshold.set", *t, cmd);
        Json inverse = items::toJson(*t);
        inverse["op"] = "threshold.set";
        *t = next;
        return inverse;
    });
    addStateOp(ops, "threshold.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"variable"});
        const std::string variable = args::string(cmd, "variable");
        auto& list = s.mutableState().thresholds;
        auto it = std::find_if(list.begin(), list.end(),
                               [&](const VariableThreshold& t) { return t.variable == variable; });
        if (it == list.end())
            throw CommandError("threshold.remove: no threshold on \"" + variable + "\"");
        Json inverse = items::toJson(*it);
        inverse["op"] = "threshold.add";
        inverse["index"] = it - list.begin();
        list.erase(it);
        return inverse;
    });
}

} // namespace faultline::core::detail
