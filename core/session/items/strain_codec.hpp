// Strain from motion as JSON: the fields of strain.add and of a session's strains[]
// ({"since_frame":0} or {"since_offset":-4}, optional "cutoff" and "prefix").
#pragma once

#include "core/motion/strain_spec.hpp"
#include "core/session/items/item_reader.hpp"

namespace faultline::core::items {

Json toJson(const StrainSpec& spec);
// Reads the fields present (since_frame or since_offset, cutoff, prefix); both references given
// fail.
void patch(StrainSpec& spec, const ItemReader& fields);
// since_frame >= 0, since_offset != 0, cutoff > 0 (or 0: automatic), a prefix of letters,
// digits, '_', '-' and '.'.
void validate(const StrainSpec& spec);

} // namespace faultline::core::items
