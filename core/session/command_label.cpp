#include "core/session/command_label.hpp"

#include <map>

namespace faultline::core {

namespace {

using Json = nlohmann::json;

std::string text(const Json& cmd, const char* field) {
    if (cmd.is_object() && cmd.contains(field) && cmd[field].is_string())
        return cmd[field].get<std::string>();
    return {};
}

std::size_t count(const Json& cmd, const char* field) {
    if (cmd.is_object() && cmd.contains(field) && cmd[field].is_array())
        return cmd[field].size();
    return 0;
}

std::string spheres(std::size_t n) { return std::to_string(n) + (n == 1 ? " sphere" : " spheres"); }

std::string quoted(const std::string& name) { return name.empty() ? std::string("it") : name; }

} // namespace

std::string describeCommand(const Json& cmd, long long spheresChanged) {
    const std::string op = text(cmd, "op");
    const std::string name = text(cmd, "name");
    if (op == "batch") {
        const std::size_t n = count(cmd, "commands");
        if (n == 1)
            return describeCommand(cmd["commands"][0]);
        // A batch of one op on several faults (Delete with several selected): say so.
        std::map<std::string, std::size_t> ops;
        for (std::size_t i = 0; i < n; ++i)
            ++ops[text(cmd["commands"][i], "op")];
        if (ops.size() == 1 && ops.begin()->first == "fault.delete")
            return "delete " + std::to_string(n) + " faults";
        // What the workbench groups around one change: the faults it left empty deleted after
        // it, the frame it ran at set before it and back after it.
        // New strain variables and the main view coloured by them (the Data panel's Add).
        const Json* change = nullptr;
        std::string emptied, colouredBy;
        bool other = false;
        for (std::size_t i = 0; i < n && !other; ++i) {
            const Json& c = cmd["commands"][i];
            const std::string cop = text(c, "op");
            if (cop == "frame.set")
                continue;
            if (cop == "fault.delete" && change)
                emptied += (emptied.empty() ? "" : ", ") + quoted(text(c, "name"));
            else if (cop == "color.set" && change && text(*change, "op") == "strain.add" &&
                     colouredBy.empty())
                colouredBy = text(c, "variable");
            else if (!change)
                change = &c;
            else
                other = true;
        }
        if (change && !other)
            return describeCommand(*change, spheresChanged) +
                   (emptied.empty() ? "" : " (deleting " + emptied + ", left empty)") +
                   (colouredBy.empty() ? "" : ", coloured by " + colouredBy);
        return std::to_string(n) + " changes";
    }
    const std::size_t moved =
        spheresChanged >= 0 ? static_cast<std::size_t>(spheresChanged) : count(cmd, "ids");
    if (op == "fault.create" && spheresChanged >= 0)
        return "make fault " + quoted(name) + " (" + spheres(moved) + ")";
    if (op == "fault.create") {
        if (text(cmd, "from") == "visible")
            return "make fault " + quoted(name) + " of the visible spheres";
        return "make fault " + quoted(name) + " (" + spheres(count(cmd, "ids")) + ")";
    }
    if (op == "fault.add")
        return "add " + spheres(moved) + " to " + quoted(name);
    if (op == "fault.remove")
        return "remove " + spheres(moved) + " from " + quoted(name);
    if (op == "fault.set") {
        if (cmd.contains("color") && !cmd.contains("notes") && !cmd.contains("rename"))
            return "recolour " + quoted(name);
        return "edit " + quoted(name);
    }
    if (op == "fault.delete")
        return "delete " + quoted(name);
    if (op == "fault.merge")
        return "merge " + std::to_string(count(cmd, "names")) + " faults into " +
               quoted(text(cmd, "into"));
    if (op == "fault.split")
        return "split " + quoted(name);
    if (op == "fault.candidates")
        return "accept the fault candidates";
    if (op == "fault.filter")
        return "show " + (text(cmd, "mode").empty() ? std::string("faults") : text(cmd, "mode"));
    const std::string variable = text(cmd, "variable");
    if (op == "threshold.add")
        return "add a " + variable + " threshold";
    if (op == "threshold.set")
        return "change the " + variable + " threshold";
    if (op == "threshold.remove")
        return "remove the " + variable + " threshold";
    if (op == "box.add")
        return "add box " + quoted(name);
    if (op == "box.set")
        return "change box " + quoted(name);
    if (op == "box.remove")
        return "remove box " + quoted(name);
    if (op == "color.set") {
        const std::string view = text(cmd, "view");
        return variable.empty() ? "recolour view " + quoted(view)
                                : "colour view " + quoted(view) + " by " + variable;
    }
    if (op == "camera.set")
        return "move the camera";
    if (op == "view.add")
        return "add view " + quoted(name);
    if (op == "view.remove")
        return "remove view " + quoted(name);
    if (op == "view.set")
        return "change view " + quoted(name);
    const std::string fault = text(cmd, "fault");
    if (op == "surface.build")
        return "build the surface of " + quoted(fault);
    if (op == "surface.set")
        return "change the surface of " + quoted(fault);
    if (op == "surface.remove")
        return "remove the surface of " + quoted(fault);
    if (op == "frame.set" && cmd.contains("frame") && cmd["frame"].is_number_integer())
        return "go to frame " + std::to_string(cmd["frame"].get<long long>());
    if (op == "data.open")
        return "open data";
    if (op == "data.close")
        return "close the data";
    if (op == "session.open")
        return "open the session";
    if (op == "session.restore")
        return "restore the session";
    if (op == "session.save")
        return "save the session";
    if (op == "layout.set")
        return "rearrange the panels";
    if (op == "strain.add" || op == "strain.remove") {
        const std::string prefix = cmd.contains("prefix") && cmd["prefix"].is_string()
                                       ? cmd["prefix"].get<std::string>()
                                       : std::string();
        return std::string(op == "strain.add" ? "add" : "remove") + " strain from motion" +
               (prefix.empty() ? "" : " (" + prefix + "*)");
    }
    if (op == "export.csv" || op == "export.vdb" || op == "export.gltf")
        return "export " + std::string(op == "export.csv"   ? "a CSV"
                                       : op == "export.vdb" ? "a VDB grid"
                                                            : "glTF");
    if (op == "render")
        return "render a figure";
    return op.empty() ? std::string("a change") : op;
}

std::string describeFailure(const nlohmann::json& cmd, const std::string& message) {
    const std::string op = cmd.is_object() && cmd.contains("op") && cmd["op"].is_string()
                               ? cmd["op"].get<std::string>()
                               : std::string();
    if (op == "undo" || op == "redo") {
        if (message == op + ": nothing to " + op)
            return "Nothing to " + op;
        return message;
    }
    std::string rest = message;
    if (!op.empty() && rest.rfind(op + ": ", 0) == 0)
        rest = rest.substr(op.size() + 2);
    else if (!op.empty() && rest.rfind(op + " ", 0) == 0)
        rest = rest.substr(op.size() + 1);
    else if (op == "batch" && cmd.contains("commands") && cmd["commands"].is_array())
        // A batch fails with the message of the command in it that failed.
        for (const auto& inner : cmd["commands"]) {
            const std::string name =
                inner.is_object() && inner.contains("op") && inner["op"].is_string()
                    ? inner["op"].get<std::string>()
                    : std::string();
            if (!name.empty() && rest.rfind(name + ": ", 0) == 0) {
                rest = rest.substr(name.size() + 2);
                break;
            }
        }
    return "Could not " + describeCommand(cmd) + ": " + rest;
}

} // namespace faultline::core
