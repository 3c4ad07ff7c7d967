// VTK legacy (.vtk) reader: POLYDATA and UNSTRUCTURED_GRID points with their POINT_DATA
// (SCALARS, VECTORS as name_x/_y/_z, FIELD arrays), ASCII or big-endian BINARY.
#pragma once

#include "core/model/frame.hpp"

#include <string>
#include <string_view>

namespace faultline::core {

bool looksLikeVtkLegacy(std::string_view head);
Frame parseVtkLegacy(const std::string& path, std::string_view bytes);

} // namespace faultline::core
