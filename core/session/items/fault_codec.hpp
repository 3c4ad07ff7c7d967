// A named fault as JSON: the fields of fault.create / fault.set, of a session's faults[] and of
// the fault a fault.restore brings back. Large member lists are packed (id_codec.hpp).
#pragma once

#include "core/faults/fault.hpp"
#include "core/session/items/item_reader.hpp"

namespace faultline::core::items {

// name, color, notes, visible and ids (or, from 4,096 members, ids_packed).
Json toJson(const Fault& fault);
// Reads the fields present; "ids" or "ids_packed" replace the members (sorted, unique).
void patch(Fault& fault, const ItemReader& fields);
// A name that is not the visible spheres' surface (kVisibleSpheres); colour components in [0, 1].
void validate(const Fault& fault);

} // namespace faultline::core::items
