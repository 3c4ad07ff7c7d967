#include "core/session/items/surface_codec.hpp"

#include "core/color/colormap.hpp"

namespace faultline::core::items {

Json toJson(const SurfaceSettings& st) {
    Json j = {{"kernel", std::string(kernelName(st.kernel))},
              {"voxel", st.voxel},
              {"iso", st.iso},
              {"visible", st.visible},
              {"opacity", st.opacity},
              {"color_by", st.colorBy},
              {"map", colorMapName(st.colorMap)}};
    j["color_reach"] = st.colorReach ? Json(*st.colorReach) : Json(nullptr);
    j["range"] = st.colorRange ? Json(*st.colorRange) : Json(nullptr);
    j["initial_color"] = st.initialColor ? Json(*st.initialColor) : Json(nullptr);
    j["color"] = st.color ? Json(*st.color) : Json(nullptr);
    return j;
}

namespace {

// An array of N finite numbers, or null for none.
template <std::size_t N>
void readOptional(const ItemReader& f, const char* field,
                  std::optional<std::array<double, N>>& into, const char* what) {
    if (!f.has(field))
        return;
    const Json& v = f.get(field);
    if (v.is_null()) {
        into.reset();
        return;
    }
    if (!v.is_array() || v.size() != N)
        f.fail(field, what, &v);
    std::array<double, N> out{};
    for (std::size_t k = 0; k < N; ++k) {
        if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
            f.fail(field, what, &v);
        out[k] = v[k].get<double>();
    }
    into = out;
}

constexpr const char* kRange = "must be [low, high] with low < high, or null";
constexpr const char* kColour = "must be [r, g, b] with components in [0, 1], or null";

// The settings' rules name their field as a reader's errors do (quoted in a command's message).
[[noreturn]] void bad(const char* field, const std::string& what) {
    throw ItemError(ItemError::Kind::Field, field, what);
}

} // namespace

void patch(SurfaceSettings& st, const ItemReader& f) {
    f.readNamed("kernel", st.kernel, parseKernel, "must be inverse, inverse-square or compact");
    f.read("voxel", st.voxel);
    f.read("iso", st.iso);
    f.read("visible", st.visible);
    f.read("opacity", st.opacity);
    f.read("color_by", st.colorBy);
    f.readNamed("map", st.colorMap, parseJournalColorMap, "names no colour map");
    readOptional<2>(f, "range", st.colorRange, kRange);
    if (f.has("color_reach")) {
        if (f.get("color_reach").is_null()) {
            st.colorReach.reset();
        } else {
            double reach = 0;
            f.read("color_reach", reach);
            st.colorReach = reach;
        }
    }
    readOptional<3>(f, "initial_color", st.initialColor, kColour);
    readOptional<3>(f, "color", st.color, kColour);
}

void validate(const SurfaceSettings& st) {
    if (st.voxel < 0)
        bad("voxel", "must be >= 0 (0: radius / 3)");
    if (!(st.iso > 0))
        bad("iso", "must be > 0");
    if (st.opacity < 0 || st.opacity > 1)
        bad("opacity", "must lie in [0, 1]");
    if (st.colorMap.kind == ColorMapKind::Palette)
        bad("map", "names no colour map");
    if (st.colorRange && !((*st.colorRange)[0] < (*st.colorRange)[1]))
        bad("range", kRange);
    if (st.colorReach && *st.colorReach < 0)
        bad("color_reach", "must be >= 0, or null for the mean radius");
    if (st.initialColor)
        for (double c : *st.initialColor)
            if (c < 0 || c > 1)
                bad("initial_color", kColour);
    if (st.color)
        for (double c : *st.color)
            if (c < 0 || c > 1)
                bad("color", kColour);
}

} // namespace faultline::core::items
