// LAMMPS / LIGGGHTS text dump reader ("ITEM: TIMESTEP ..."), one or many frames per file.
// Indexing finds frame offsets in one streaming pass; a frame is parsed from its byte range.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct LammpsFrameIndex {
    std::uint64_t offset = 0;    // first byte of the frame (uncompressed stream)
    std::uint64_t length = 0;    // bytes up to the next frame or the end
    std::uint64_t firstLine = 1; // line number of the frame's first line
    std::int64_t timestep = 0;
    std::uint64_t atoms = 0;
};

// One pass over the file: where each frame starts, its timestep and atom count.
// Throws InputError on a malformed header or a truncated frame.
// partial: see indexTextFrames (text_lines.hpp).
std::vector<LammpsFrameIndex> indexLammpsDump(const std::string& path,
                                              std::string* partial = nullptr);

// Parses one frame from its text (as located by the index). `firstLine` numbers errors.
Frame parseLammpsDumpFrame(const std::string& path, std::string_view text,
                           std::uint64_t firstLine = 1);

// True when `head` (the first bytes of a file) looks like a LAMMPS dump.
bool looksLikeLammpsDump(std::string_view head);

} // namespace faultline::core
