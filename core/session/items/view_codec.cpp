#include "core/session/items/view_codec.hpp"

#include "core/color/colormap.hpp"
#include "core/session/items/camera_codec.hpp"

#include <cmath>

namespace faultline::core::items {

Json toJson(const ViewState& v) {
    return {{"name", v.name},
            {"frame", {{"relative", v.frame.relative}, {"value", v.frame.value}}},
            {"color",
             {{"variable", v.colorVariable},
              {"map", colorMapName(v.colorMap)},
              {"range_mode", std::string(rangeModeName(v.rangeMode))},
              {"range", v.range},
              {"difference",
               {{"mode", differenceModeName(v.difference.mode)},
                {"reference",
                 {{"relative", v.difference.reference.relative},
                  {"value", v.difference.reference.value}}}}}}},
            {"camera", toJson(v.camera)},
            {"linked_camera", v.linkedCamera},
            {"context_points", v.contextPoints}};
}

namespace {

// A whole number (a frame or an offset).
void readWhole(const ItemReader& f, const char* field, long long& out) {
    if (!f.has(field))
        return;
    double d = 0;
    f.read(field, d);
    if (d != std::trunc(d) || std::fabs(d) > 9e15)
        f.fail(field, "must be a whole number", &f.get(field));
    out = static_cast<long long>(d);
}

void readBinding(const ItemReader& f, FrameBinding& b) {
    f.read("relative", b.relative);
    readWhole(f, "value", b.value);
}

} // namespace

namespace {
const std::string& colorMapChoices() {
    static const std::string text = [] {
        std::string known;
        for (const std::string& name : colorMapNames())
            known += (known.empty() ? "" : ", ") + name;
        return "names no colour map (" + known + ")";
    }();
    return text;
}
} // namespace

void patchColor(ViewState& v, const ItemReader& c) {
    c.read("variable", v.colorVariable);
    c.readNamed("map", v.colorMap, parseJournalColorMap, colorMapChoices().c_str());
    c.readNamed("range_mode", v.rangeMode, parseRangeMode,
                "must be frame, all, fixed or percentile");
    if (c.has("range")) {
        const Json& r = c.get("range");
        if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number() ||
            !std::isfinite(r[0].get<double>()) || !std::isfinite(r[1].get<double>()))
            c.fail("range", "must be [low, high]", &r);
        v.range = {r[0].get<double>(), r[1].get<double>()};
    }
}

void patch(ViewState& v, const ItemReader& f) {
    f.read("name", v.name);
    if (f.has("frame"))
        readBinding(ItemReader(f.get("frame"), f.path("frame.")), v.frame);
    if (f.has("color")) {
        const ItemReader c(f.get("color"), f.path("color."));
        patchColor(v, c);
        if (c.has("difference")) {
            const ItemReader d(c.get("difference"), c.path("difference."));
            d.readNamed("mode", v.difference.mode, parseDifferenceMode,
                        "must be none, change or displacement");
            if (d.has("reference"))
                readBinding(ItemReader(d.get("reference"), d.path("reference.")),
                            v.difference.reference);
        }
    }
    if (f.has("camera"))
        patch(v.camera, ItemReader(f.get("camera"), f.path("camera.")));
    f.read("linked_camera", v.linkedCamera);
    f.read("context_points", v.contextPoints);
}

void validate(const ViewState& v) {
    if (v.name.empty())
        breaks("name", "must not be empty");
    if (!v.frame.relative && v.frame.value < 0)
        breaks("frame.value", "must be >= 0 for a fixed frame");
    if (v.colorMap.kind == ColorMapKind::Palette)
        breaks("color.map", "names no colour map");
    if (!(v.range[0] < v.range[1]))
        breaks("color.range", "must have low < high");
    if (v.difference.mode == ColorDifference::Mode::Change && v.colorVariable.empty())
        breaks("color.difference.mode", "change needs a variable");
    if (!v.difference.reference.relative && v.difference.reference.value < 0)
        breaks("color.difference.reference.value", "must be >= 0 for a fixed frame");
    validate(v.camera, "camera.");
}

} // namespace faultline::core::items
