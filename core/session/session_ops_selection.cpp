// Ops on what is selected: box.add/set/remove, threshold.add/set/remove (JOURNAL.md).
#include "core/session/session_ops.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::core::detail {

namespace {

void checkBounds(const char* op, const std::array<double, 3>& mn, const std::array<double, 3>& mx) {
    for (int a = 0; a < 3; ++a)
        if (!(mn[a] <= mx[a]))
            throw CommandError(std::string(op) + ": min must not exceed max on any axis");
}

BoxMode modeArg(const Json& cmd, BoxMode fallback) {
    auto mode = args::optionalString(cmd, "mode");
    if (!mode)
        return fallback;
    auto parsed = parseBoxMode(*mode);
    if (!parsed)
        throw CommandError(cmd["op"].get<std::string>() + ": \"mode\" must be keep or cut, found \"" + *mode + "\"");
    return *parsed;
}

template <typename T> std::size_t indexArg(const Json& cmd, const std::vector<T>& items) {
    const long long i = args::optionalInteger(cmd, "index").value_or(static_cast<long long>(items.size()));
    return static_cast<std::size_t>(std::clamp(i, 0LL, static_cast<long long>(items.size())));
}

Json thresholdJson(const VariableThreshold& t) {
    return {{"variable", t.variable}, {"low", t.low}, {"high", t.high}, {"enabled", t.enabled}};
}

} // namespace

void registerSelectionOps(OpTable& ops) {
    addStateOp(ops, "box.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "min", "max", "mode", "enabled", "index"});
        CuttingBox b;
        b.name = args::string(cmd, "name");
        if (b.name.empty() || s.state().box(b.name))
            throw CommandError("box.add: a box named \"" + b.name + "\" exists already");
        b.min = args::vec3(cmd, "min");
        b.max = args::vec3(cmd, "max");
        checkBounds("box.add", b.min, b.max);
        b.mode = modeArg(cmd, BoxMode::Keep);
        b.enabled = args::optionalBool(cmd, "enabled").value_or(true);
        auto& boxes = s.mutableState().boxes;
        boxes.insert(boxes.begin() + static_cast<long>(indexArg(cmd, boxes)), b);
        return {{"op", "box.remove"}, {"name", b.name}};
    });
    addStateOp(ops, "box.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "min", "max", "mode", "enabled", "rename"});
        const std::string name = args::string(cmd, "name");
        CuttingBox* b = s.mutableState().box(name);
        if (!b)
            throw CommandError("box.set: no box named \"" + name + "\"");
        CuttingBox next = *b;
        next.min = args::optionalVec3(cmd, "min").value_or(b->min);
        next.max = args::optionalVec3(cmd, "max").value_or(b->max);
        checkBounds("box.set", next.min, next.max);
        next.mode = modeArg(cmd, b->mode);
        next.enabled = args::optionalBool(cmd, "enabled").value_or(b->enabled);
        if (auto rename = args::optionalString(cmd, "rename")) {
            if (rename->empty() || (*rename != name && s.state().box(*rename)))
                throw CommandError("box.set: cannot rename to \"" + *rename + "\"");
            next.name = *rename;
        }
        Json inverse = boxToJson(*b);
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
        auto it = std::find_if(boxes.begin(), boxes.end(), [&](const CuttingBox& b) { return b.name == name; });
        if (it == boxes.end())
            throw CommandError("box.remove: no box named \"" + name + "\"");
        Json inverse = boxToJson(*it);
        inverse["op"] = "box.add";
        inverse["index"] = it - boxes.begin();
        boxes.erase(it);
        return inverse;
    });

    addStateOp(ops, "threshold.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"variable", "low", "high", "enabled", "index"});
        VariableThreshold t;
        t.variable = args::string(cmd, "variable");
        if (t.variable.empty() || s.state().threshold(t.variable))
            throw CommandError("threshold.add: \"" + t.variable +
                               "\" has a threshold already (use threshold.set)");
        t.low = args::optionalNumber(cmd, "low").value_or(-1e30);
        t.high = args::optionalNumber(cmd, "high").value_or(1e30);
        if (t.low > t.high)
            throw CommandError("threshold.add: low must not exceed high");
        t.enabled = args::optionalBool(cmd, "enabled").value_or(true);
        auto& list = s.mutableState().thresholds;
        list.insert(list.begin() + static_cast<long>(indexArg(cmd, list)), t);
        return {{"op", "threshold.remove"}, {"variable", t.variable}};
    });
    addStateOp(ops, "threshold.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"variable", "low", "high", "enabled"});
        const std::string variable = args::string(cmd, "variable");
        VariableThreshold* t = s.mutableState().threshold(variable);
        if (!t)
            throw CommandError("threshold.set: no threshold on \"" + variable + "\"");
        VariableThreshold next = *t;
        next.low = args::optionalNumber(cmd, "low").value_or(t->low);
        next.high = args::optionalNumber(cmd, "high").value_or(t->high);
        next.enabled = args::optionalBool(cmd, "enabled").value_or(t->enabled);
        if (next.low > next.high)
            throw CommandError("threshold.set: low must not exceed high");
        Json inverse = thresholdJson(*t);
        inverse["op"] = "threshold.set";
        *t = next;
        return inverse;
    });
    addStateOp(ops, "threshold.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"variable"});
        const std::string variable = args::string(cmd, "variable");
        auto& list = s.mutableState().thresholds;
        auto it = std::find_if(list.begin(), list.end(), [&](const VariableThreshold& t) { return t.variable == variable; });
        if (it == list.end())
            throw CommandError("threshold.remove: no threshold on \"" + variable + "\"");
        Json inverse = thresholdJson(*it);
        inverse["op"] = "threshold.add";
        inverse["index"] = it - list.begin();
        list.erase(it);
        return inverse;
    });
}

} // namespace faultline::core::detail
