// Surface nets on the stored leaves of a sparse density grid: one vertex per cell that the
// iso-surface crosses (the mean of its edge crossings, as OpenVDB's volumeToMesh places them at
// adaptivity 0), one quad per crossing edge. Vertex colour and gradient are trilinear in the
// cell over its stored voxels; the gradient at a voxel by central differences of the density.
// Leaves are meshed in parallel and joined by a prefix sum, so the result does not depend on the
// thread count.
#pragma once

#include "core/surface/fault_surface.hpp"

#include <openvdb/openvdb.h>

#include <array>
#include <cmath>

namespace faultline::core::detail {

// Meshes `density` at `iso` (inside where density > iso; triangles counter-clockwise seen from
// outside). Voxel (i, j, k) sits at world (i, j, k) * h. Fills positions, colors, indices, and
// with `normals` the normals (-gradient normalised); otherwise normals is left empty.
// Only edges between voxels of stored leaves and their neighbours are looked at: tiles must lie
// on one side of every iso asked for (the surface plan's margin guarantees it).
// The outward unit normal where the density has gradient g (the density falls outwards), or +z
// where g vanishes.
inline std::array<float, 3> normalFromGradient(const std::array<float, 3>& g) {
    const float len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    return len > 0.0f ? std::array<float, 3>{-g[0] / len, -g[1] / len, -g[2] / len}
                      : std::array<float, 3>{0.0f, 0.0f, 1.0f};
}

void surfaceNets(const openvdb::FloatGrid& density, const openvdb::Vec3SGrid& color, bool normals,
                 float iso, float h, SurfaceMesh& mesh);

} // namespace faultline::core::detail
