#include "core/session/session_state.hpp"

#include "core/color/colormap.hpp"
#include "core/surface/surface_params.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace faultline::core {

std::string_view differenceModeName(ColorDifference::Mode mode) {
    switch (mode) {
    case ColorDifference::Mode::Change:
        return "change";
    case ColorDifference::Mode::Displacement:
        return "displacement";
    case ColorDifference::Mode::None:
        break;
    }
    return "none";
}

std::size_t referenceFrame(const ViewState& view, std::size_t shown, std::size_t count) {
    const FrameBinding& ref = view.difference.reference;
    const long long f = ref.relative ? static_cast<long long>(shown) + ref.value : ref.value;
    return static_cast<std::size_t>(
        std::clamp(f, 0LL, std::max(1LL, static_cast<long long>(count)) - 1));
}

std::string colorTitle(const ViewState& view, std::size_t referenceFrame) {
    const std::string since = " since frame " + std::to_string(referenceFrame);
    switch (view.difference.mode) {
    case ColorDifference::Mode::Change:
        return view.colorVariable.empty() ? std::string() : view.colorVariable + " change" + since;
    case ColorDifference::Mode::Displacement:
        return "displacement" + since;
    case ColorDifference::Mode::None:
        break;
    }
    return view.colorVariable;
}

std::optional<ColorDifference::Mode> parseDifferenceMode(std::string_view name) {
    for (auto m : {ColorDifference::Mode::None, ColorDifference::Mode::Change,
                   ColorDifference::Mode::Displacement})
        if (differenceModeName(m) == name)
            return m;
    return std::nullopt;
}

namespace {
template <typename Vec, typename Key> auto findIn(Vec& items, Key key, std::string_view name) {
    auto it =
        std::find_if(items.begin(), items.end(), [&](const auto& e) { return e.*key == name; });
    return it == items.end() ? nullptr : &*it;
}
} // namespace

ViewState* SessionState::view(std::string_view name) {
    return findIn(views, &ViewState::name, name);
}
const ViewState* SessionState::view(std::string_view name) const {
    return findIn(views, &ViewState::name, name);
}
CuttingBox* SessionState::box(std::string_view name) {
    return findIn(boxes, &CuttingBox::name, name);
}
const CuttingBox* SessionState::box(std::string_view name) const {
    return findIn(boxes, &CuttingBox::name, name);
}
const VariableThreshold* SessionState::threshold(std::string_view variable) const {
    return findIn(thresholds, &VariableThreshold::variable, variable);
}
const SurfaceSettings* SessionState::surface(std::string_view fault) const {
    return findIn(surfaces, &SurfaceSettings::fault, fault);
}
VariableThreshold* SessionState::threshold(std::string_view variable) {
    return findIn(thresholds, &VariableThreshold::variable, variable);
}
Fault* SessionState::fault(std::string_view name) { return findIn(faults, &Fault::name, name); }
const Fault* SessionState::fault(std::string_view name) const {
    return findIn(faults, &Fault::name, name);
}
SurfaceSettings* SessionState::surface(std::string_view fault) {
    return findIn(surfaces, &SurfaceSettings::fault, fault);
}

nlohmann::json surfaceSettingsFields(const SurfaceSettings& st) {
    nlohmann::json j = {{"kernel", std::string(kernelName(st.kernel))},
                        {"voxel", st.voxel},
                        {"iso", st.iso},
                        {"visible", st.visible},
                        {"opacity", st.opacity},
                        {"color_by", st.colorBy},
                        {"map", st.colorMap}};
    j["color_reach"] = st.colorReach ? nlohmann::json(*st.colorReach) : nlohmann::json(nullptr);
    j["range"] = st.colorRange ? nlohmann::json(*st.colorRange) : nlohmann::json(nullptr);
    j["initial_color"] =
        st.initialColor ? nlohmann::json(*st.initialColor) : nlohmann::json(nullptr);
    return j;
}

void readSurfaceSettingsFields(const nlohmann::json& j, SurfaceSettings& st) {
    auto bad = [](const char* field, const char* what) {
        throw std::invalid_argument(std::string("\"") + field + "\" " + what);
    };
    auto number = [&](const char* field, double& into) {
        if (!j.contains(field))
            return;
        if (!j[field].is_number() || !std::isfinite(j[field].get<double>()))
            bad(field, "must be a number");
        into = j[field].get<double>();
    };
    auto text = [&](const char* field, std::string& into) {
        if (!j.contains(field))
            return;
        if (!j[field].is_string())
            bad(field, "must be a string");
        into = j[field].get<std::string>();
    };
    // An array of N finite numbers, or null for none.
    auto numbers = [&]<std::size_t N>(const char* field, std::optional<std::array<double, N>>& into,
                                      const char* what) {
        if (!j.contains(field))
            return;
        const auto& v = j[field];
        if (v.is_null()) {
            into.reset();
            return;
        }
        if (!v.is_array() || v.size() != N)
            bad(field, what);
        std::array<double, N> out{};
        for (std::size_t k = 0; k < N; ++k) {
            if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
                bad(field, what);
            out[k] = v[k].get<double>();
        }
        into = out;
    };
    if (j.contains("kernel")) {
        std::string name;
        text("kernel", name);
        const auto kernel = parseKernel(name);
        if (!kernel)
            bad("kernel", "must be inverse, inverse-square or compact");
        st.kernel = *kernel;
    }
    number("voxel", st.voxel);
    number("iso", st.iso);
    if (j.contains("visible")) {
        if (!j["visible"].is_boolean())
            bad("visible", "must be true or false");
        st.visible = j["visible"].get<bool>();
    }
    number("opacity", st.opacity);
    text("color_by", st.colorBy);
    text("map", st.colorMap);
    numbers.operator()<2>("range", st.colorRange, "must be [low, high] with low < high, or null");
    if (j.contains("color_reach")) {
        if (j["color_reach"].is_null()) {
            st.colorReach.reset();
        } else {
            double reach = 0;
            number("color_reach", reach);
            st.colorReach = reach;
        }
    }
    numbers.operator()<3>("initial_color", st.initialColor,
                          "must be [r, g, b] with components in [0, 1], or null");
    if (st.voxel < 0)
        bad("voxel", "must be >= 0 (0: radius / 3)");
    if (!(st.iso > 0))
        bad("iso", "must be > 0");
    if (st.opacity < 0 || st.opacity > 1)
        bad("opacity", "must lie in [0, 1]");
    const auto map = parseColorMap(st.colorMap);
    if (!map || map->kind == ColorMapKind::Palette)
        bad("map", "names no colour map");
    st.colorMap = colorMapName(*map); // one name per map ("grey" is "gray"): one cache entry
    if (st.colorRange && !((*st.colorRange)[0] < (*st.colorRange)[1]))
        bad("range", "must be [low, high] with low < high, or null");
    if (st.colorReach && *st.colorReach < 0)
        bad("color_reach", "must be >= 0, or null for the mean radius");
    if (st.initialColor)
        for (double c : *st.initialColor)
            if (c < 0 || c > 1)
                bad("initial_color", "must be [r, g, b] with components in [0, 1], or null");
}

} // namespace faultline::core
