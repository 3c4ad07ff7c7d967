// A fault surface as the renderer takes it: the core's mesh flattened into MeshData's columns.
#pragma once

#include "core/surface/fault_surface.hpp"
#include "ui/render/renderer.hpp"

namespace faultline::ui {

MeshData toMeshData(const core::SurfaceMesh& mesh);

} // namespace faultline::ui
