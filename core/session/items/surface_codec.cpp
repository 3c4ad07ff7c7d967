#include "core/session/items/surface_codec.hpp"

#include "core/color/colormap.hpp"

namespace faultline::core::items {

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

Json optional(const auto& value) { return value ? Json(*value) : Json(nullptr); }

// Each field once: its JSON and how it is read ("range", "color_reach", "initial_color" and
// "color" take null for none).
const Field<SurfaceSettings> kFields[] = {
    {"kernel", [](const SurfaceSettings& st) { return Json(std::string(kernelName(st.kernel))); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         f.readNamed(n, st.kernel, parseKernel, "must be inverse, inverse-square or compact");
     }},
    member<SurfaceSettings, &SurfaceSettings::voxel>("voxel"),
    member<SurfaceSettings, &SurfaceSettings::iso>("iso"),
    member<SurfaceSettings, &SurfaceSettings::visible>("visible"),
    member<SurfaceSettings, &SurfaceSettings::opacity>("opacity"),
    member<SurfaceSettings, &SurfaceSettings::colorBy>("color_by"),
    {"map", [](const SurfaceSettings& st) { return Json(colorMapName(st.colorMap)); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         f.readNamed(n, st.colorMap, parseJournalColorMap, "names no colour map");
     }},
    {"range", [](const SurfaceSettings& st) { return optional(st.colorRange); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         readOptional<2>(f, n, st.colorRange, kRange);
     }},
    {"color_reach", [](const SurfaceSettings& st) { return optional(st.colorReach); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         if (!f.has(n))
             return;
         if (f.get(n).is_null()) {
             st.colorReach.reset();
             return;
         }
         double reach = 0;
         f.read(n, reach);
         st.colorReach = reach;
     }},
    {"initial_color", [](const SurfaceSettings& st) { return optional(st.initialColor); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         readOptional<3>(f, n, st.initialColor, kColour);
     }},
    {"color", [](const SurfaceSettings& st) { return optional(st.color); },
     [](SurfaceSettings& st, const ItemReader& f, const char* n) {
         readOptional<3>(f, n, st.color, kColour);
     }},
};

} // namespace

Json toJson(const SurfaceSettings& st) { return fieldsToJson(st, kFields); }

void patch(SurfaceSettings& st, const ItemReader& f) { patchFields(st, f, kFields); }

std::vector<std::string> surfaceFieldNames() { return fieldNames(kFields); }

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
