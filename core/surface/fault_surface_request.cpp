#include "core/surface/fault_surface_request.hpp"

#include "core/session/session.hpp"

#include <bit>

namespace faultline::core {

FaultSpheres gatherFaultSpheres(const Frame& frame, const Fault& fault) {
    FaultSpheres s;
    for (std::int64_t id : fault.ids)
        if (auto row = frame.rowOf(id)) {
            s.x.push_back(frame.x[*row]);
            s.y.push_back(frame.y[*row]);
            s.z.push_back(frame.z[*row]);
            s.radius.push_back(frame.radius[*row]);
            s.rgb.insert(s.rgb.end(), fault.color.begin(), fault.color.end());
        }
    return s;
}

SurfaceParams surfaceParamsOf(const SurfaceSettings& settings, const Fault& fault) {
    SurfaceParams params;
    const auto kernel = parseKernel(settings.kernel);
    if (!kernel)
        throw CommandError("surface: \"kernel\" must be inverse, inverse-square or compact");
    params.kernel = *kernel;
    params.iso = static_cast<float>(settings.iso);
    params.voxelSize = static_cast<float>(settings.voxel);
    params.initialColor = fault.color;
    return params;
}

SurfaceKey surfaceKeyOf(std::size_t frameIndex, const Fault& fault, const SurfaceParams& params) {
    std::uint64_t members = hashMemberIds(fault.ids);
    for (float c : fault.color)
        members = (members ^ std::bit_cast<std::uint32_t>(c)) * 0x100000001b3ull;
    return {static_cast<std::int64_t>(frameIndex), members, fieldParamsHash(params)};
}

} // namespace faultline::core
