#include "core/session/items/box_codec.hpp"

namespace faultline::core::items {

Json toJson(const CuttingBox& b) {
    return {{"name", b.name},
            {"min", b.min},
            {"max", b.max},
            {"mode", std::string(boxModeName(b.mode))},
            {"enabled", b.enabled}};
}

void patch(CuttingBox& b, const ItemReader& f) {
    f.read("name", b.name);
    f.read("min", b.min);
    f.read("max", b.max);
    f.readNamed("mode", b.mode, parseBoxMode, "must be keep or cut");
    f.read("enabled", b.enabled);
}

void validate(const CuttingBox& b) {
    if (b.name.empty())
        breaks("name", "must not be empty");
    for (int a = 0; a < 3; ++a)
        if (!(b.min[a] <= b.max[a]))
            breaks("min", "must not exceed max on any axis");
}

} // namespace faultline::core::items
