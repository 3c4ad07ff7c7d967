// VTK XML readers: .vtu / .vtp points with PointData (ascii, base64 binary with UInt32 or
// UInt64 headers, appended raw, zlib-compressed blocks), and .pvd collections as time series.
#pragma once

#include "core/model/frame.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

bool looksLikeVtkXml(std::string_view head);        // a VTKFile that is not a Collection
bool looksLikeVtkCollection(std::string_view head); // a VTKFile of type Collection (.pvd)

Frame parseVtkXml(const std::string& path, std::string_view bytes);

struct CollectionEntry {
    double time = 0.0;
    std::string file; // as written in the .pvd (relative to the .pvd's folder unless absolute)
};
std::vector<CollectionEntry> parseVtkCollection(const std::string& path, std::string_view bytes);

} // namespace faultline::core
