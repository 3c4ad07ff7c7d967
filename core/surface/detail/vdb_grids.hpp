// The OpenVDB side of a SurfaceField. Include only from the few .cpp files that need the grids:
// OpenVDB headers are slow to compile.
#pragma once

#include "core/surface/fault_surface.hpp"
#include "core/surface/metaball_field.hpp"

#include <openvdb/openvdb.h>

#include <array>
#include <memory>
#include <mutex>

namespace faultline::core {

struct SurfaceField::Impl {
    SurfaceParams params;
    float isoMin = 0.0f, isoMax = 0.0f;
    SurfaceStats stats;
    std::unique_ptr<MetaballField> field; // for analytic normals at new vertices
    openvdb::FloatGrid::Ptr density;
    openvdb::Vec3SGrid::Ptr color;
    // isoSliderRange(), computed once on first use (the field is shared by re-meshes).
    mutable std::once_flag sliderOnce;
    mutable std::array<float, 2> slider{0.0f, 0.0f};
};

// openvdb::initialize(), once per process.
void ensureOpenVdbInitialized();

} // namespace faultline::core
