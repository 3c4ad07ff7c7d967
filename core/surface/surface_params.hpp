// SurfaceParams: everything that decides a fault surface (kernel, iso-value, voxel, colour).
// Parsed once from journal strings into enums; hashed for the SurfaceCache key.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace faultline::core {

// The paper's field f(x) = sum_i w_i / d(x, c_i)^p with w_i = r_i (eq. 1, Algorithm 1),
// or Wyvill's compact kernel w_i (1 - d^2 / R_i^2)^3 for d < R_i = compactReach * r_i.
enum class MetaballKernel { Inverse, InverseSquare, Compact };

std::string_view kernelName(MetaballKernel kernel); // "inverse" | "inverse-square" | "compact"
std::optional<MetaballKernel> parseKernel(std::string_view name);

struct SurfaceParams {
    MetaballKernel kernel = MetaballKernel::InverseSquare;
    float iso = 1.0f;
    // Voxel edge in world units; 0 picks the mean sphere radius / 3.
    float voxelSize = 0.0f;
    // Largest |f - f_exact| at every stored voxel, as a fraction of the lowest supported iso.
    float tolerance = 1e-3f;
    // The grid holds exact values for every iso in [iso / f, iso * f]: re-meshing there needs
    // no new field. Larger ranges cost more voxels.
    float isoRangeFactor = 1.05f;
    // Figure 4: a field point takes the colour of each sphere whose radius + colorReach holds it
    // (averaged where several do), else initialColor.
    float colorReach = 0.0f;
    std::array<float, 3> initialColor{1.0f, 1.0f, 1.0f};
    // Support radius of the compact kernel as a multiple of each sphere's radius.
    float compactReach = 3.0f;
    // Refuse builds whose grids and mesh would need more than this.
    std::size_t memoryBudgetBytes = std::size_t{2} << 30;

    bool operator==(const SurfaceParams&) const = default;
};

// The voxel size a build will use (resolves the 0 default against the spheres' mean radius).
float resolvedVoxelSize(const SurfaceParams& params, double meanRadius);

// Hash of every parameter that changes the field and colour grids (everything except iso).
std::uint64_t fieldParamsHash(const SurfaceParams& params);

} // namespace faultline::core
