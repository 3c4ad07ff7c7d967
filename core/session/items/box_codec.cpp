#include "core/session/items/box_codec.hpp"

namespace faultline::core::items {

namespace {
// Each field once: its JSON and how it is read.
using B = CuttingBox;
const Field<B> kFields[] = {
    member<B, &B::name>("name"),
    member<B, &B::min>("min"),
    member<B, &B::max>("max"),
    {"mode", [](const B& b) { return Json(std::string(boxModeName(b.mode))); },
     [](B& b, const ItemReader& f, const char* n) {
         f.readNamed(n, b.mode, parseBoxMode, "must be keep or cut");
     }},
    member<B, &B::enabled>("enabled"),
};
} // namespace

Json toJson(const CuttingBox& b) { return fieldsToJson(b, kFields); }

void patch(CuttingBox& b, const ItemReader& f) { patchFields(b, f, kFields); }

std::vector<std::string> boxFieldNames() { return fieldNames(kFields); }

void validate(const CuttingBox& b) {
    if (b.name.empty())
        breaks("name", "must not be empty");
    for (int a = 0; a < 3; ++a)
        if (!(b.min[a] <= b.max[a]))
            breaks("min", "must not exceed max on any axis");
}

} // namespace faultline::core::items
