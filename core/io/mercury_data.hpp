// MercuryDPM's .data files (its "xballs" output): per time step a header line
// "N time xmin ymin zmin xmax ymax zmax" (2-D: "N time xmin ymin xmax ymax") and N rows
// "x y z vx vy vz radius alpha beta gamma omex omey omez species" (2-D:
// "x y vx vy radius theta omega species"), steps one after another in one file.
#pragma once

#include "core/model/frame.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct MercuryFrameIndex {
    std::uint64_t offset = 0, length = 0;
    std::uint64_t firstLine = 1;
    std::uint64_t particles = 0;
    double time = 0; // the header's simulation time
};

// A first line of 6 or 8 numbers starting with a count, then (unless the count is 0) a row of 8
// or 14 numbers to match.
bool looksLikeMercuryData(std::string_view head);

// One pass: where each time step starts. InputError (line) on a bad header or a truncated step.
// partial: see indexTextFrames (text_lines.hpp).
std::vector<MercuryFrameIndex> indexMercuryData(const std::string& path,
                                                std::string* partial = nullptr);

// One time step. Ids are row numbers (the format has none); attributes vx vy vz,
// orientation_x/y/z (2-D: orientation), angular_velocity_x/y/z (2-D: angular_velocity),
// species; the header's bounds become the box.
Frame parseMercuryDataFrame(const std::string& path, std::string_view text,
                            std::uint64_t firstLine = 1);

} // namespace faultline::core
