#include "core/session/session_json.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/session/atomic_file.hpp"
#include "core/session/id_codec.hpp"
#include "core/session/items/item_codecs.hpp"

#include <cmath>
#include <filesystem>

namespace faultline::core {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

std::string relativeIfPossible(const std::string& path, const std::string& baseDir) {
    if (baseDir.empty() || path.empty())
        return path;
    std::error_code ec;
    const fs::path rel = fs::path(path).lexically_relative(fs::path(baseDir));
    if (rel.empty() || ec)
        return path;
    return rel.generic_string();
}

std::string resolve(const std::string& path, const std::string& baseDir) {
    if (path.empty() || fs::path(path).is_absolute() || baseDir.empty())
        return path;
    return (fs::path(baseDir) / path).lexically_normal().string();
}

// One item read by its codec (items/*_codec.hpp), errors located in the file.
template <typename T>
T readItem(const Json& j, const std::string& where, const std::string& file,
           std::initializer_list<const char*> required, T item = {}) {
    try {
        const items::ItemReader fields(j);
        for (const char* f : required)
            fields.require(f);
        items::patch(item, fields);
        items::validate(item);
    } catch (const items::ItemError& e) {
        throw InputError(file, items::fileMessage(where, e));
    }
    return item;
}

// Migrations from older schemas, each from N to N+1. Schema 1 is the first: none yet.
Json migrate(Json doc, int from, const std::string& path) {
    (void)path;
    (void)from;
    return doc;
}

} // namespace

Json sessionToJson(const SessionState& s, const std::string& baseDir) {
    Json doc;
    doc["format"] = "faultline-session";
    doc["schema"] = kSessionSchema;
    Json paths = Json::array();
    for (const auto& p : s.dataPaths)
        paths.push_back(relativeIfPossible(p, baseDir));
    doc["data"] = {{"paths", paths}};
    doc["frame"] = s.frame;
    Json views = Json::array();
    for (const auto& v : s.views)
        views.push_back(items::toJson(v));
    doc["views"] = views;
    Json boxes = Json::array();
    for (const auto& b : s.boxes)
        boxes.push_back(items::toJson(b));
    doc["boxes"] = boxes;
    Json thresholds = Json::array();
    for (const auto& t : s.thresholds)
        thresholds.push_back(items::toJson(t));
    doc["thresholds"] = thresholds;
    Json faults = Json::array();
    for (const auto& f : s.faults)
        faults.push_back(items::toJson(f));
    doc["faults"] = faults;
    doc["fault_filter"] = {{"mode", faultFilterModeName(s.faultFilter.mode)},
                           {"fault", s.faultFilter.fault}};
    Json surfaces = Json::array();
    for (const auto& sf : s.surfaces) {
        Json j = items::toJson(sf);
        j["fault"] = sf.fault;
        surfaces.push_back(std::move(j));
    }
    doc["surfaces"] = surfaces;
    if (!s.strains.empty()) {
        Json strains = Json::array();
        for (const auto& st : s.strains)
            strains.push_back(items::toJson(st));
        doc["strains"] = strains;
    }
    doc["dock_layout"] = s.dockLayout.is_null() ? Json::object() : s.dockLayout;
    return doc;
}

SessionState sessionFromJson(const Json& input, const std::string& baseDir,
                             const std::string& path) {
    // Not value("format", ...): a "format" that is no string would throw the library's error.
    if (!input.is_object() || !input.contains("format") || input["format"] != "faultline-session")
        throw InputError(path,
                         "not a Faultline session (expected \"format\": \"faultline-session\")");
    if (!input.contains("schema") || !input["schema"].is_number_integer())
        throw InputError(path, "session has no integer \"schema\" version");
    const int schema = input["schema"].get<int>();
    if (schema > kSessionSchema)
        throw InputError(path, "session schema " + std::to_string(schema) +
                                   " is newer than this Faultline understands (" +
                                   std::to_string(kSessionSchema) + "): please update Faultline");
    if (schema < 1)
        throw InputError(path, "session schema " + std::to_string(schema) + " is not valid");
    const Json doc = schema < kSessionSchema ? migrate(input, schema, path) : input;

    // The document's own fields read as the items' are (items::ItemReader), errors located in
    // the file; the items themselves through their codecs (readItem).
    auto at = [](const char* list, std::size_t k) {
        return std::string(list) + "[" + std::to_string(k) + "]";
    };
    SessionState s;
    try {
        const items::ItemReader top(doc);
        if (top.has("data")) {
            const items::ItemReader data(top.get("data"), "data.");
            const Json& paths = data.array("paths");
            for (std::size_t k = 0; k < paths.size(); ++k) {
                if (!paths[k].is_string())
                    data.fail(at("paths", k).c_str(), "must be a string");
                s.dataPaths.push_back(resolve(paths[k].get<std::string>(), baseDir));
            }
        }
        double frame = 0.0;
        top.read("frame", frame);
        if (frame < 0 || frame != std::floor(frame))
            top.fail("frame", "must be a whole number >= 0");
        s.frame = static_cast<std::size_t>(frame);

        s.views.clear();
        const Json& views = top.array("views");
        for (std::size_t k = 0; k < views.size(); ++k) {
            ViewState view = readItem<ViewState>(views[k], at("views", k), path, {"name"});
            for (const auto& other : s.views)
                if (other.name == view.name)
                    throw InputError(path, at("views", k) + ".name: '" + view.name +
                                               "' is used by two views");
            s.views.push_back(std::move(view));
        }
        if (!s.view("main"))
            s.views.insert(s.views.begin(), mainView());

        const Json& boxes = top.array("boxes");
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            const CuttingBox box =
                readItem<CuttingBox>(boxes[k], at("boxes", k), path, {"name", "min", "max"});
            if (s.box(box.name))
                throw InputError(path, at("boxes", k) + ".name: '" + box.name + "' is used twice");
            s.boxes.push_back(box);
        }
        const Json& thresholds = top.array("thresholds");
        for (std::size_t k = 0; k < thresholds.size(); ++k) {
            const VariableThreshold th = readItem<VariableThreshold>(
                thresholds[k], at("thresholds", k), path, {"variable", "low", "high"});
            if (s.threshold(th.variable))
                throw InputError(path, at("thresholds", k) + ".variable: '" + th.variable +
                                           "' has two thresholds");
            s.thresholds.push_back(th);
        }
        const Json& strains = top.array("strains");
        for (std::size_t k = 0; k < strains.size(); ++k) {
            const StrainSpec st = readItem<StrainSpec>(strains[k], at("strains", k), path, {});
            if (!strains[k].contains("since_frame") && !strains[k].contains("since_offset"))
                throw InputError(path,
                                 at("strains", k) + ": needs \"since_frame\" or \"since_offset\"");
            for (const auto& other : s.strains)
                if (other.prefix == st.prefix)
                    throw InputError(path, at("strains", k) + ".prefix: '" + st.prefix +
                                               "' is used twice");
            s.strains.push_back(st);
        }
        const Json& faults = top.array("faults");
        for (std::size_t k = 0; k < faults.size(); ++k) {
            Fault fault = readItem<Fault>(faults[k], at("faults", k), path, {"name"});
            if (s.fault(fault.name))
                throw InputError(path,
                                 at("faults", k) + ".name: '" + fault.name + "' is used twice");
            s.faults.push_back(std::move(fault));
        }
        if (top.has("fault_filter")) {
            const items::ItemReader ff(top.get("fault_filter"), "fault_filter.");
            std::string mode = "all";
            ff.read("mode", mode);
            if (const auto m = parseFaultFilterMode(mode))
                s.faultFilter.mode = *m;
            else
                ff.fail("mode", "must be " + faultFilterModeNames());
            ff.read("fault", s.faultFilter.fault);
            if (s.faultFilter.mode == FaultFilter::Mode::Only && !s.fault(s.faultFilter.fault))
                ff.fail("fault", "names no fault of this session");
        }
        const Json& surfaces = top.array("surfaces");
        for (std::size_t k = 0; k < surfaces.size(); ++k) {
            const items::ItemReader sf(surfaces[k], at("surfaces", k) + ".");
            SurfaceSettings st;
            sf.require("fault");
            sf.read("fault", st.fault);
            if (!s.hasSurfaceSource(st.fault))
                sf.fail("fault", "names no fault of this session");
            s.surfaces.push_back(
                readItem<SurfaceSettings>(surfaces[k], at("surfaces", k), path, {}, st));
        }
        if (top.has("dock_layout")) {
            if (!top.get("dock_layout").is_object())
                top.fail("dock_layout", "must be an object");
            s.dockLayout = top.get("dock_layout");
        }
    } catch (const items::ItemError& e) {
        throw InputError(path, items::fileMessage("", e));
    }
    return s;
}

Json parseJsonText(const std::string& text, const std::string& path, std::size_t maxDepth) {
    Json::parser_callback_t limitDepth = [&](int depth, Json::parse_event_t, Json&) {
        if (static_cast<std::size_t>(depth) > maxDepth)
            throw InputError(path,
                             "JSON nested deeper than " + std::to_string(maxDepth) + " levels");
        return true;
    };
    try {
        return Json::parse(text, limitDepth);
    } catch (const Json::parse_error& e) {
        std::string msg = e.what();
        const auto colon = msg.find("syntax error");
        throw InputError(path, InputError::Where::Byte, e.byte,
                         "invalid JSON: " + (colon != std::string::npos ? msg.substr(colon) : msg));
    } catch (const Json::exception& e) {
        // e.g. out_of_range for a number beyond double (1e999): found by fuzz_journal.
        std::string msg = e.what();
        const auto bracket = msg.find("] ");
        throw InputError(path, "invalid JSON: " +
                                   (bracket != std::string::npos ? msg.substr(bracket + 2) : msg));
    }
}

SessionState loadSessionFile(const std::string& path) {
    constexpr std::uint64_t kMaxSessionBytes = 2ull << 30;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec)
        throw InputError(path, "cannot open: " + ec.message());
    if (size > kMaxSessionBytes)
        throw InputError(path, "session file is larger than 2 GiB: refused");
    const std::string text = readFileBytes(path);
    const Json doc = parseJsonText(text, path);
    const std::string dir = fs::absolute(fs::path(path)).parent_path().string();
    return sessionFromJson(doc, dir, path);
}

void saveSessionFile(const SessionState& state, const std::string& path) {
    const std::string dir = fs::absolute(fs::path(path)).parent_path().string();
    writeFileAtomically(path, sessionToJson(state, dir).dump(1) + "\n");
}

} // namespace faultline::core
