// Ops on fault surfaces (JOURNAL.md): surface.build (settings + a checked build), surface.set /
// surface.remove (settings only; undo of each other), export.vdb and export.gltf.
#include "core/session/session_ops.hpp"

#include "core/session/fault_surface_request.hpp"
#include "core/session/items/item_codecs.hpp"
#include "core/surface/fault_surface.hpp"
#include "core/surface/surface_export.hpp"

#include <algorithm>

namespace faultline::core::detail {

namespace {

Json settingsJson(const SurfaceSettings& st) {
    Json j = items::toJson(st);
    j["op"] = "surface.set";
    j["fault"] = st.fault;
    return j;
}

// surface.build's and surface.set's fields: "fault" and the settings' (one table, in the codec).
void onlySurfaceFields(const Json& cmd) {
    static const std::vector<std::string> fields = items::surfaceFieldNames();
    args::onlyFields(cmd, {"fault"}, fields);
}

// What a surface named `name` is built from in the current frame: the fault as formed there
// (its members passing the thresholds), or the visible spheres (kVisibleSpheres).
Fault sourceOf(Session& s, const std::string& name, const char* op) {
    if (isVisibleSpheres(name)) {
        auto frame = s.currentFrame();
        if (!frame)
            throw CommandError(std::string(op) + ": no data is open");
        return visibleSpheresFault(*frame, s.visibility());
    }
    const Fault* fault = s.state().fault(name);
    if (!fault)
        throw CommandError(std::string(op) + ": no fault named \"" + name + "\"");
    auto frame = s.currentFrame();
    return frame ? faultAsFormed(*frame, *fault, s.state().thresholds) : *fault;
}

// The settings a command asks for, over the fault's current ones.
SurfaceSettings settingsFrom(Session& s, const Json& cmd, const char* op) {
    const std::string fault = args::string(cmd, "fault");
    if (!s.state().hasSurfaceSource(fault))
        throw CommandError(std::string(op) + ": no fault named \"" + fault + "\"");
    SurfaceSettings st;
    st.fault = fault;
    const SurfaceSettings* old = s.state().surface(fault);
    if (old)
        st = *old;
    // "iso":"wrap" (and surface.build without "iso"): the iso-value that wraps the spheres,
    // worked out once the other settings are read (it depends on kernel and voxel).
    const bool explicitWrap =
        cmd.contains("iso") ? cmd["iso"] == "wrap" : std::string(op) == "surface.build";
    bool isoWrap = explicitWrap;
    Json fields = cmd;
    if (isoWrap)
        fields.erase("iso");
    try {
        items::patch(st, items::ItemReader(fields));
        items::validate(st);
    } catch (const items::ItemError& e) {
        throw CommandError(items::commandMessage(op, e) +
                           (e.path == "iso" && !isoWrap ? " (or \"wrap\")" : ""));
    }
    // surface.set without "iso" for a new surface, or with another kernel, under an inverse
    // kernel: the wrapping iso too, as the workbench's Surfaces panel gives. The default of 1
    // lies far outside the field of a few hundred spheres or more (r/d or r/d^2 summed over
    // them), whose surface is then one ball around them all. The compact kernel's field is a
    // sum of bumps, where 1 keeps its meaning (and recorded journals their figures). With no
    // data open or no member formed in this frame, the default stays.
    const bool implicitWrap = !explicitWrap && !cmd.contains("iso") &&
                              st.kernel != MetaballKernel::Compact &&
                              (!old || old->kernel != st.kernel);
    isoWrap = explicitWrap || (implicitWrap && s.currentFrame());
    if (isoWrap) {
        auto frame = s.currentFrame();
        if (!frame)
            throw CommandError(std::string(op) + ": no data is open");
        try {
            if (auto iso = faultWrappingIso(*frame, sourceOf(s, fault, op), st))
                st.iso = *iso;
        } catch (const std::exception& e) {
            throw CommandError(std::string(op) + ": " + e.what());
        }
    }
    return st;
}

Json storeSettings(Session& s, const SurfaceSettings& st) {
    auto& surfaces = s.mutableState().surfaces;
    auto it = std::find_if(surfaces.begin(), surfaces.end(),
                           [&](const SurfaceSettings& e) { return e.fault == st.fault; });
    Json inverse = it == surfaces.end() ? Json{{"op", "surface.remove"}, {"fault", st.fault}}
                                        : settingsJson(*it);
    if (it == surfaces.end())
        surfaces.push_back(st);
    else
        *it = st;
    return inverse;
}

// Builds the surface into the session's cache (the exports take it from there); refuses what
// cannot be built.
void build(Session& s, const SurfaceSettings& st, const char* op) {
    auto frame = s.currentFrame();
    if (!frame)
        throw CommandError(std::string(op) + ": no data is open");
    const Fault fault = sourceOf(s, st.fault, op);
    if (fault.ids.empty() && !isVisibleSpheres(st.fault))
        if (const Fault* whole = s.state().fault(st.fault); whole && !whole->ids.empty())
            throw CommandError(std::string(op) + ": none of " + st.fault + "'s " +
                               std::to_string(whole->ids.size()) +
                               " spheres passes the thresholds in frame " +
                               std::to_string(s.state().frame) + ": it has not formed there yet");
    try {
        SurfaceReuse reuse = surfaceReuseFor(s, s.state().frame);
        reuse.keepOnly = true; // no copy of a mesh nobody reads here
        buildFaultSurface(*frame, {fault, st}, nullptr, reuse);
    } catch (const std::exception& e) {
        throw CommandError(std::string(op) + ": " + e.what());
    }
}

SurfaceSettings settingsOf(Session& s, const std::string& fault, const char* op) {
    if (const SurfaceSettings* st = s.state().surface(fault))
        return *st;
    if (!s.state().hasSurfaceSource(fault))
        throw CommandError(std::string(op) + ": no fault named \"" + fault + "\"");
    SurfaceSettings st; // never built: the defaults
    st.fault = fault;
    return st;
}

FaultSurfaceRequest requestOf(Session& s, const std::string& fault, const char* op) {
    const SurfaceSettings st = settingsOf(s, fault, op);
    return {sourceOf(s, fault, op), st};
}

std::shared_ptr<const Frame> frameOf(Session& s, const char* op) {
    auto frame = s.currentFrame();
    if (!frame)
        throw CommandError(std::string(op) + ": no data is open");
    return frame;
}

} // namespace

void registerSurfaceOps(OpRegistry& ops) {
    addStateOp(ops, "surface.build", [](Session& s, const Json& cmd) -> Json {
        onlySurfaceFields(cmd);
        const SurfaceSettings st = settingsFrom(s, cmd, "surface.build");
        build(s, st, "surface.build"); // a request that cannot be built is refused here
        return storeSettings(s, st);
    });
    addStateOp(ops, "surface.set", [](Session& s, const Json& cmd) -> Json {
        onlySurfaceFields(cmd);
        return storeSettings(s, settingsFrom(s, cmd, "surface.set"));
    });
    addStateOp(ops, "surface.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"fault"});
        const std::string fault = args::string(cmd, "fault");
        auto& surfaces = s.mutableState().surfaces;
        auto it = std::find_if(surfaces.begin(), surfaces.end(),
                               [&](const SurfaceSettings& e) { return e.fault == fault; });
        if (it == surfaces.end())
            throw CommandError("surface.remove: fault \"" + fault + "\" has no surface");
        Json inverse = settingsJson(*it);
        surfaces.erase(it);
        return inverse;
    });
    addAction(ops, "export.vdb", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"fault", "path"});
        const FaultSurfaceRequest request = requestOf(s, args::string(cmd, "fault"), "export.vdb");
        const std::string path = s.outputPath(args::string(cmd, "path"));
        try {
            const auto frame = frameOf(s, "export.vdb");
            writeFaultVdb(*frame, request, path, nullptr, surfaceReuseFor(s, s.state().frame));
        } catch (const std::exception& e) {
            throw CommandError(std::string("export.vdb: ") + e.what());
        }
        return nullptr;
    });
    addAction(ops, "export.gltf", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"faults", "path", "glyphs"});
        const auto names = args::strings(cmd, "faults");
        if (names.empty())
            throw CommandError("export.gltf: \"faults\" names no fault");
        std::vector<FaultSurfaceRequest> requests;
        for (const auto& name : names)
            requests.push_back(requestOf(s, name, "export.gltf"));
        const std::string path = s.outputPath(args::string(cmd, "path"));
        try {
            const auto frame = frameOf(s, "export.gltf");
            writeFaultsGlb(*frame, requests, path,
                           args::optionalBool(cmd, "glyphs").value_or(false), nullptr,
                           surfaceReuseFor(s, s.state().frame));
        } catch (const std::exception& e) {
            throw CommandError(std::string("export.gltf: ") + e.what());
        }
        return nullptr;
    });
}

} // namespace faultline::core::detail

namespace faultline::core {

FaultSurfaceRequest surfaceRequestFor(Session& s, const std::string& fault, const char* op) {
    return detail::requestOf(s, fault, op);
}

} // namespace faultline::core
