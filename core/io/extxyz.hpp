// XYZ and extended XYZ (ASE, OVITO, QUIP: a "Properties=name:type:columns:..." comment line), one
// or many frames per file. Each frame: a line with the particle count, a comment line (key=value
// pairs in extended XYZ), then one row per particle. Types: R real, I integer, L logical (T/F),
// S string (a species name becomes an integer attribute, 1 for the first name seen, ...).
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct XyzFrameIndex {
    std::uint64_t offset = 0, length = 0; // bytes of the frame in the (uncompressed) file
    std::uint64_t firstLine = 1;
    std::uint64_t atoms = 0;
    std::int64_t timestep = 0; // "Timestep=" or "step=" of the comment, else the frame's number
};

// True when the first bytes look like (extended) XYZ: a line holding only a count, then a
// comment line, then rows whose first value is a name or whose comment has "Properties=".
bool looksLikeXyz(std::string_view head);

// One pass: where each frame starts. InputError (line) on a bad count or a truncated frame.
// partial: see indexTextFrames (text_lines.hpp).
std::vector<XyzFrameIndex> indexXyz(const std::string& path, std::string* partial = nullptr);

// One frame from its bytes. Positions: "pos" (or "positions"); ids: "id"/"ID"/"Identifier"
// (else row numbers); radius: "radius"/"Radius" (or "diameter", halved). Other numeric columns
// become attributes (vectors as name_x, name_y, name_z). InputError names line and column.
Frame parseXyzFrame(const std::string& path, std::string_view text, std::uint64_t firstLine = 1);

} // namespace faultline::core
