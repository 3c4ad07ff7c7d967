#include "core/session/commands.hpp"

#include "core/session/items/box_codec.hpp"
#include "core/session/items/camera_codec.hpp"

namespace faultline::core::cmd {

namespace {
Json op(const char* name) { return Json{{"op", name}}; }
Json op(const char* name, const char* key, Json value) {
    Json j = op(name);
    j[key] = std::move(value);
    return j;
}
Json op(const char* name, const char* key, Json value, const char* key2, Json value2) {
    Json j = op(name, key, std::move(value));
    j[key2] = std::move(value2);
    return j;
}
} // namespace

Json undo() { return op("undo"); }
Json redo() { return op("redo"); }

Json batch(std::vector<Json> commands) {
    if (commands.size() == 1)
        return std::move(commands.front());
    return op("batch", "commands", Json(std::move(commands)));
}

Json frameSet(std::size_t frame) { return op("frame.set", "frame", frame); }
Json dataOpen(const std::vector<std::string>& paths) { return op("data.open", "paths", paths); }
Json dataClose() { return op("data.close"); }
Json sessionSave(const std::string& path) { return op("session.save", "path", path); }
Json sessionOpen(const std::string& path, const std::vector<std::string>& data) {
    Json j = op("session.open", "path", path);
    if (!data.empty())
        j["data"] = data;
    return j;
}
Json layoutSet(Json layout) { return op("layout.set", "layout", std::move(layout)); }

Json boxAdd(const std::string& name, const std::array<double, 3>& min,
            const std::array<double, 3>& max, BoxMode mode) {
    Json j = op("box.add", "name", name);
    j["min"] = min;
    j["max"] = max;
    j["mode"] = std::string(boxModeName(mode));
    return j;
}
Json boxAdd(const CuttingBox& box) {
    Json j = items::toJson(box);
    j["op"] = "box.add";
    return j;
}
Json boxRemove(const std::string& name) { return op("box.remove", "name", name); }
BoxSet& BoxSet::mode(BoxMode m) {
    m_json["mode"] = std::string(boxModeName(m));
    return *this;
}

Json thresholdRemove(const std::string& variable) {
    return op("threshold.remove", "variable", variable);
}

Json viewRemove(const std::string& name) { return op("view.remove", "name", name); }
CameraSet& CameraSet::all(const CameraState& camera) {
    const Json fields = items::toJson(camera); // kept alive: items() refers to it
    for (const auto& [key, value] : fields.items())
        m_json[key] = value;
    return *this;
}
ColorSet& ColorSet::range(double low, double high) {
    m_json["range"] = {low, high};
    return *this;
}
ColorSet& ColorSet::rangeMode(RangeMode mode) {
    m_json["range_mode"] = std::string(rangeModeName(mode));
    return *this;
}
ColorSet& ColorSet::difference(ColorDifference::Mode mode) {
    m_json["difference"] = std::string(differenceModeName(mode));
    return *this;
}

Json strainRemove(const std::string& prefix) { return op("strain.remove", "prefix", prefix); }

Json faultCreateVisible(const std::string& name) {
    return op("fault.create", "name", name, "from", "visible");
}
Json faultAdd(const std::string& name, std::vector<std::int64_t> ids) {
    return op("fault.add", "name", name, "ids", std::move(ids));
}
Json faultAddVisible(const std::string& name) {
    return op("fault.add", "name", name, "from", "visible");
}
Json faultRemove(const std::string& name, std::vector<std::int64_t> ids) {
    return op("fault.remove", "name", name, "ids", std::move(ids));
}
Json faultDelete(const std::string& name) { return op("fault.delete", "name", name); }
Json faultMerge(const std::vector<std::string>& names, const std::string& into) {
    return op("fault.merge", "names", names, "into", into);
}
Json faultSplit(const std::string& name) { return op("fault.split", "name", name); }
Json faultFilter(const FaultFilter& filter) {
    Json j = op("fault.filter", "mode", std::string(faultFilterModeName(filter.mode)));
    if (filter.mode == FaultFilter::Mode::Only)
        j["fault"] = filter.fault;
    return j;
}

FaultCandidates& FaultCandidates::method(CandidateMethod m) {
    m_json["method"] = std::string(candidateMethodName(m));
    return *this;
}

SurfaceSet& SurfaceSet::kernel(MetaballKernel k) {
    m_json["kernel"] = std::string(kernelName(k));
    return *this;
}
SurfaceSet& SurfaceSet::color(const std::optional<std::array<double, 3>>& c) {
    m_json["color"] = c ? Json(*c) : Json(nullptr);
    return *this;
}
SurfaceSet& SurfaceSet::colorReach(std::optional<double> reach) {
    m_json["color_reach"] = reach ? Json(*reach) : Json(nullptr);
    return *this;
}
SurfaceSet& SurfaceSet::range(double low, double high) {
    m_json["range"] = {low, high};
    return *this;
}
SurfaceSet& SurfaceSet::clearRange() {
    m_json["range"] = nullptr;
    return *this;
}
Json surfaceRemove(const std::string& fault) { return op("surface.remove", "fault", fault); }

Render::Render(const std::string& view, const std::string& path, int width, int height)
    : Command("render", "view", view) {
    m_json["path"] = path;
    m_json["size"] = {width, height};
}
Render& Render::frames(long long first, long long last) {
    m_json["frames"] = {first, last};
    return *this;
}

Json exportCsv(const std::string& what, const std::string& path) {
    return op("export.csv", "what", what, "path", path);
}
Json exportVdb(const std::string& fault, const std::string& path) {
    return op("export.vdb", "fault", fault, "path", path);
}
Json exportGltf(const std::vector<std::string>& faults, const std::string& path, bool glyphs) {
    Json j = op("export.gltf", "faults", faults);
    j["path"] = path;
    if (glyphs)
        j["glyphs"] = true;
    return j;
}

} // namespace faultline::core::cmd
