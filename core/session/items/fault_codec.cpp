#include "core/session/items/fault_codec.hpp"

#include "core/session/id_codec.hpp"
#include "core/session/session_state.hpp" // isVisibleSpheres

namespace faultline::core::items {

namespace {
// Faults this large store their members packed; smaller ones stay readable.
constexpr std::size_t kPackIdsFrom = 4096;
} // namespace

Json toJson(const Fault& f) {
    Json j = {{"name", f.name}, {"color", f.color}, {"notes", f.notes}, {"visible", f.visible}};
    if (f.ids.size() >= kPackIdsFrom)
        j["ids_packed"] = packSortedIds(f.ids);
    else
        j["ids"] = f.ids;
    return j;
}

void patch(Fault& fault, const ItemReader& f) {
    f.read("name", fault.name);
    f.read("color", fault.color);
    f.read("notes", fault.notes);
    f.read("visible", fault.visible);
    if (f.has("ids") && f.has("ids_packed"))
        f.fail("ids_packed", "cannot stand beside \"ids\"");
    if (f.has("ids_packed")) {
        std::string packed, error;
        f.read("ids_packed", packed);
        auto ids = unpackSortedIds(packed, error);
        if (!ids)
            f.fail("ids_packed", error);
        fault.ids = std::move(*ids);
    } else if (f.has("ids")) {
        const Json& ids = f.get("ids");
        if (!ids.is_array())
            f.fail("ids",
                   std::string("must be an array of particle ids, found ") + ids.type_name());
        std::vector<std::int64_t> out;
        out.reserve(ids.size());
        for (const Json& id : ids) {
            if (!id.is_number_integer())
                f.fail("ids", "must hold whole numbers", &id);
            out.push_back(id.get<std::int64_t>());
        }
        normalizeIds(out);
        fault.ids = std::move(out);
    }
}

void validate(const Fault& f) {
    if (f.name.empty())
        breaks("name", "must not be empty");
    if (isVisibleSpheres(f.name))
        breaks("name", "\"" + f.name + "\" names the visible spheres' surface, not a fault");
    for (float c : f.color)
        if (!(c >= 0.0f && c <= 1.0f))
            breaks("color", "components must lie in [0, 1]");
}

} // namespace faultline::core::items
