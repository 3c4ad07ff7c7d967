// Surface planning: which 8^3 voxel blocks can hold the iso-surface for any iso in a range,
// found by octree descent with guaranteed field bounds, and the memory check before any work.
#pragma once

#include "core/surface/interrupter.hpp"
#include "core/surface/metaball_field.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace faultline::core {

struct SurfacePlan {
    float isoMin = 0.0f, isoMax = 0.0f;
    std::vector<Coord3> blocks; // block origins (voxel index, multiples of 8) to evaluate
    // Voxel boxes (inclusive) where f > isoMax everywhere: stored as tiles, never evaluated.
    std::vector<std::pair<Coord3, Coord3>> inside;
    std::size_t estimatedBytes = 0;
};

// Bytes a build needs per evaluated block (density 2 KiB, colour 6 KiB, mesh share), for the
// budget check.
inline constexpr std::size_t kBytesPerBlock = 16 * 1024;

// Throws SurfaceRequestError when the surface would need more than `budgetBytes`, saying how much
// it would need, or when the region does not fit OpenVDB's index range.
SurfacePlan planSurface(const MetaballField& field, float isoMin, float isoMax,
                        std::size_t budgetBytes, Interrupter* interrupter);

// Human-readable byte count ("1.5 GiB").
std::string formatBytes(double bytes);

} // namespace faultline::core
