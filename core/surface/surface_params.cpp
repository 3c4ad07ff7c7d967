#include "core/surface/surface_params.hpp"
#include "core/util/enum_names.hpp"

#include <bit>
#include <cstring>

namespace faultline::core {

namespace {
constexpr EnumName<MetaballKernel> kKernels[] = {{MetaballKernel::Inverse, "inverse"},
                                                 {MetaballKernel::InverseSquare, "inverse-square"},
                                                 {MetaballKernel::Compact, "compact"}};
} // namespace

std::string_view kernelName(MetaballKernel kernel) { return nameIn(kKernels, kernel); }

std::optional<MetaballKernel> parseKernel(std::string_view name) { return valueIn(kKernels, name); }

float resolvedVoxelSize(const SurfaceParams& params, double meanRadius) {
    if (params.voxelSize > 0.0f)
        return params.voxelSize;
    return static_cast<float>(meanRadius / 3.0);
}

namespace {
void mix(std::uint64_t& h, std::uint64_t v) {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdull;
}
void mixFloat(std::uint64_t& h, float f) { mix(h, std::bit_cast<std::uint32_t>(f)); }
} // namespace

std::uint64_t fieldParamsHash(const SurfaceParams& p) {
    std::uint64_t h = 0x5eed;
    mix(h, static_cast<std::uint64_t>(p.kernel));
    mixFloat(h, p.voxelSize);
    mixFloat(h, p.tolerance);
    mixFloat(h, p.isoRangeFactor);
    mixFloat(h, p.colorReach);
    for (float c : p.initialColor)
        mixFloat(h, c);
    mixFloat(h, p.compactReach);
    mix(h, p.memoryBudgetBytes);
    return h;
}

} // namespace faultline::core
