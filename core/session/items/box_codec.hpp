// A cutting box as JSON: the fields of box.add / box.set and of a session's boxes[].
#pragma once

#include "core/selection/cutting_box.hpp"
#include "core/session/items/item_reader.hpp"

namespace faultline::core::items {

Json toJson(const CuttingBox& box);
// Reads the fields present (name, min, max, mode, enabled).
void patch(CuttingBox& box, const ItemReader& fields);
// The fields, in the table they are declared in once (what box.add and box.set accept besides
// "index" and "rename").
std::vector<std::string> boxFieldNames();
// A name; min <= max on every axis.
void validate(const CuttingBox& box);

} // namespace faultline::core::items
