// Ops on what is shown: data.open/close, frame.set, view.*, color.set, camera.set, layout.set.
#include "core/session/session_ops.hpp"

#include "core/color/colormap.hpp"
#include "core/session/items/item_codecs.hpp"

#include <algorithm>

namespace faultline::core::detail {

namespace {

Json openInverse(Session& s) {
    if (!s.dataset())
        return {{"op", "data.close"}};
    return {{"op", "data.open"}, {"paths", s.state().dataPaths}, {"frame", s.state().frame}};
}

ViewState& viewOf(Session& s, const Json& cmd, const char* field = "view") {
    const std::string name = cmd.contains(field) ? args::string(cmd, field) : std::string("main");
    ViewState* v = s.mutableState().view(name);
    if (!v)
        throw CommandError(cmd["op"].get<std::string>() + ": no view named \"" + name + "\"");
    return *v;
}

} // namespace

void registerDataOps(OpRegistry& ops) {
    addStateOp(ops, "data.open", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"paths", "frame"});
        std::vector<std::string> paths = args::strings(cmd, "paths");
        if (paths.empty())
            throw CommandError("data.open: \"paths\" is empty");
        if (!s.dataOverride().empty())
            paths = s.dataOverride(); // replay --data: the same analysis on another run
        for (auto& p : paths)
            p = s.inputPath(p);
        std::shared_ptr<Dataset> ds;
        try {
            ds = s.openDataset(paths);
        } catch (const InputError& e) {
            throw CommandError(std::string("data.open: ") + e.what());
        }
        std::size_t frame = s.state().frame;
        if (auto f = args::optionalInteger(cmd, "frame")) {
            if (*f < 0 || static_cast<std::size_t>(*f) >= ds->frameCount())
                throw CommandError("data.open: frame " + std::to_string(*f) + " out of range 0.." +
                                   std::to_string(ds->frameCount() - 1));
            frame = static_cast<std::size_t>(*f);
        }
        Json inverse = openInverse(s);
        s.mutableState().dataPaths = paths;
        s.mutableState().frame = std::min(frame, ds->frameCount() - 1);
        s.setDataset(std::move(ds));
        return inverse;
    });
    addStateOp(ops, "data.close", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {});
        Json inverse = openInverse(s);
        s.mutableState().dataPaths.clear();
        s.mutableState().frame = 0;
        s.setDataset(nullptr);
        return inverse;
    });
    addStateOp(ops, "frame.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"frame"});
        const long long f = args::integer(cmd, "frame");
        if (!s.dataset())
            throw CommandError("frame.set: no data is open");
        const long long count = static_cast<long long>(s.dataset()->frameCount());
        if (f < 0 || f >= count)
            throw CommandError("frame.set: frame " + std::to_string(f) + " out of range 0.." +
                               std::to_string(count - 1));
        Json inverse = {{"op", "frame.set"}, {"frame", s.state().frame}};
        s.mutableState().frame = static_cast<std::size_t>(f);
        return inverse;
    });
    addStateOp(ops, "view.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "frame", "offset", "index"});
        const std::string name = args::string(cmd, "name");
        if (name.empty() || s.state().view(name))
            throw CommandError("view.add: a view named \"" + name + "\" exists already");
        if (cmd.contains("frame") && cmd.contains("offset"))
            throw CommandError(
                "view.add: give \"frame\" (absolute) or \"offset\" (relative), not both");
        ViewState v = *s.state().view("main"); // same colours and camera as the main view
        v.name = name;
        if (auto f = args::optionalInteger(cmd, "frame")) {
            if (*f < 0)
                throw CommandError("view.add: frame must be >= 0");
            v.frame = {false, *f};
        } else {
            v.frame = {true, args::optionalInteger(cmd, "offset").value_or(0)};
        }
        auto& views = s.mutableState().views;
        const auto index =
            std::min<std::size_t>(static_cast<std::size_t>(std::max(
                                      0LL, args::optionalInteger(cmd, "index")
                                               .value_or(static_cast<long long>(views.size())))),
                                  views.size());
        items::checked("view.add", v);
        views.insert(views.begin() + static_cast<long>(index), v);
        return {{"op", "view.remove"}, {"name", name}};
    });
    addStateOp(ops, "view.restore", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"view", "index"});
        const ViewState v = items::patchedField("view.restore", ViewState{}, cmd, "view", {"name"});
        if (s.state().view(v.name))
            throw CommandError("view.restore: a view named \"" + v.name + "\" exists already");
        auto& views = s.mutableState().views;
        const auto index =
            std::min<std::size_t>(static_cast<std::size_t>(std::max(
                                      0LL, args::optionalInteger(cmd, "index").value_or(0))),
                                  views.size());
        views.insert(views.begin() + static_cast<long>(index), v);
        return {{"op", "view.remove"}, {"name", v.name}};
    });
    addStateOp(ops, "view.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name"});
        const std::string name = args::string(cmd, "name");
        if (name == "main")
            throw CommandError("view.remove: the main view cannot be removed");
        auto& views = s.mutableState().views;
        auto it = std::find_if(views.begin(), views.end(),
                               [&](const ViewState& v) { return v.name == name; });
        if (it == views.end())
            throw CommandError("view.remove: no view named \"" + name + "\"");
        Json inverse = {
            {"op", "view.restore"}, {"view", items::toJson(*it)}, {"index", it - views.begin()}};
        views.erase(it);
        return inverse;
    });
    addStateOp(ops, "view.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "frame", "offset", "linked_camera", "context_points"});
        ViewState& v = viewOf(s, cmd, "name");
        if (cmd.contains("frame") && cmd.contains("offset"))
            throw CommandError(
                "view.set: give \"frame\" (absolute) or \"offset\" (relative), not both");
        Json inverse = {{"op", "view.set"},
                        {"name", v.name},
                        {"linked_camera", v.linkedCamera},
                        {"context_points", v.contextPoints}};
        inverse[v.frame.relative ? "offset" : "frame"] = v.frame.value;
        FrameBinding binding = v.frame;
        if (auto f = args::optionalInteger(cmd, "frame")) {
            if (*f < 0)
                throw CommandError("view.set: frame must be >= 0");
            binding = {false, *f};
        }
        if (auto o = args::optionalInteger(cmd, "offset"))
            binding = {true, *o};
        const bool linked = args::optionalBool(cmd, "linked_camera").value_or(v.linkedCamera);
        const bool context = args::optionalBool(cmd, "context_points").value_or(v.contextPoints);
        ViewState next = v;
        next.frame = binding;
        next.linkedCamera = linked;
        next.contextPoints = context;
        items::checked("view.set", next);
        v = next;
        return inverse;
    });
    addStateOp(ops, "color.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"view", "variable", "map", "range", "range_mode", "difference",
                               "since_frame", "since_offset"});
        ViewState& v = viewOf(s, cmd);
        Json inverse = {{"op", "color.set"},
                        {"view", v.name},
                        {"variable", v.colorVariable},
                        {"map", colorMapName(v.colorMap)},
                        {"range_mode", std::string(rangeModeName(v.rangeMode))},
                        {"range", v.range},
                        {"difference", differenceModeName(v.difference.mode)}};
        inverse[v.difference.reference.relative ? "since_offset" : "since_frame"] =
            v.difference.reference.value;
        ViewState next = v;
        // The view codec reads what color.set shares with a view's "color" (variable, map,
        // range_mode, range) and checks the whole view, so the op and session files agree.
        const items::ItemReader fields(cmd);
        try {
            items::patchColor(next, fields);
            fields.readNamed("difference", next.difference.mode, parseDifferenceMode,
                             "must be none, change or displacement");
        } catch (const items::ItemError& e) {
            throw CommandError(items::commandMessage("color.set", e));
        }
        if (cmd.contains("range") && !cmd.contains("range_mode"))
            next.rangeMode = RangeMode::Fixed; // a range given is the range shown
        if (cmd.contains("since_frame") && cmd.contains("since_offset"))
            throw CommandError("color.set: give \"since_frame\" (absolute) or \"since_offset\" "
                               "(relative), not both");
        if (auto f = args::optionalInteger(cmd, "since_frame")) {
            if (*f < 0)
                throw CommandError("color.set: \"since_frame\" must be >= 0");
            next.difference.reference = {false, *f};
        }
        if (auto o = args::optionalInteger(cmd, "since_offset"))
            next.difference.reference = {true, *o};
        items::checked("color.set", next);
        v = next;
        return inverse;
    });
    addStateOp(ops, "camera.set", [](Session& s, const Json& cmd) -> Json {
        static const std::vector<std::string> fields = items::cameraFieldNames();
        args::onlyFields(cmd, {"view"}, fields); // the camera's fields: one table, in its codec
        ViewState& v = viewOf(s, cmd);
        const CameraState c = items::patched("camera.set", v.camera, cmd);
        Json inverse = items::toJson(v.camera);
        inverse["op"] = "camera.set";
        inverse["view"] = v.name;
        // Linked cameras move together.
        for (auto& other : s.mutableState().views)
            if (&other == &v || (v.linkedCamera && other.linkedCamera))
                other.camera = c;
        return inverse;
    });
    addStateOp(ops, "layout.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"layout"});
        const Json& layout = args::require(cmd, "layout");
        if (!layout.is_object())
            throw CommandError("layout.set: \"layout\" must be an object");
        Json inverse = {
            {"op", "layout.set"},
            {"layout", s.state().dockLayout.is_null() ? Json::object() : s.state().dockLayout}};
        s.mutableState().dockLayout = layout;
        return inverse;
    });
}

} // namespace faultline::core::detail
