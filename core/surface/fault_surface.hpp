// Fault surfaces: the implicit metaball surface through a set of spheres (paper eq. 1, Fig. 4),
// kept as sparse density + colour grids so a new iso-value re-meshes without a new field.
#pragma once

#include "core/surface/interrupter.hpp"
#include "core/surface/sphere_set.hpp"
#include "core/surface/surface_params.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace faultline::core {

// What the renderer draws: indexed triangles with per-vertex normals and float RGB colours.
struct SurfaceMesh {
    std::vector<std::array<float, 3>> positions;
    std::vector<std::array<float, 3>> normals; // unit, pointing out of the surface (down f)
    std::vector<std::array<float, 3>> colors;  // RGB in [0, 1]
    std::vector<std::uint32_t> indices;        // three per triangle, counter-clockwise from outside
    std::size_t triangleCount() const { return indices.size() / 3; }
};

struct SurfaceStats {
    std::size_t blocks = 0; // evaluated 8^3 blocks
    std::size_t activeVoxels = 0;
    std::size_t coarseNodes = 0; // nodes on the multilevel grids
    int levels = 0;
    int anterpolatedLevels = 0; // coarse levels that sum grid charges instead of spheres
    float nearCutoff = 0.0f;
    int kappa = 0;               // near cutoff / level-1 spacing
    double estimatedError = 0.0; // a priori bound on |f - f_exact| of the levels built
    double planSeconds = 0.0, fieldSeconds = 0.0, meshSeconds = 0.0;
    // fieldSeconds in parts: the coarse levels (prepare), the blocks' values, their colours.
    double levelsSeconds = 0.0, blocksSeconds = 0.0, colorSeconds = 0.0;
};

// The grids of one build (opaque: OpenVDB stays inside a few .cpp files). Immutable once built,
// so a cache and a background job can share it.
class SurfaceField {
  public:
    struct Impl;
    explicit SurfaceField(std::unique_ptr<Impl> impl);
    ~SurfaceField();

    const SurfaceParams& params() const;
    float voxelSize() const;
    std::size_t sphereCount() const;
    // Iso-values this grid re-meshes exactly: [iso / isoRangeFactor, iso * isoRangeFactor].
    float isoMin() const;
    float isoMax() const;
    bool supportsIso(float iso) const { return iso >= isoMin() && iso <= isoMax(); }
    const SurfaceStats& stats() const;
    // Smallest and largest value the density grid stores (values are clamped at 4 isoMax): an
    // empty mesh at an iso above the largest says the iso lies above the field everywhere.
    std::array<float, 2> storedRange() const;
    // The largest field value at a sample of the sphere centres (up to 256): about the field's
    // maximum (for the compact kernel; the inverse kernels grow without bound at a centre).
    float maxAtCentres() const;
    // The iso-values worth a slider for these spheres and this kernel (core::isoSliderRange),
    // computed on the first call (about a tenth of a second at most) and kept.
    std::array<float, 2> isoSliderRange() const;
    std::size_t memoryBytes() const;
    const Impl& impl() const { return *m_impl; }

  private:
    std::unique_ptr<Impl> m_impl;
};

struct SurfaceResult {
    std::shared_ptr<const SurfaceField> field;
    SurfaceMesh mesh;
    float iso = 0.0f;
};

// Builds the field, colour and mesh. Throws SurfaceRequestError before any work for a bad
// request (no spheres, bad numbers, over the memory budget: the message says how much it would
// need) and SurfaceCancelled when the interrupter asks to stop.
SurfaceResult buildSurface(const SphereSet& spheres, const SurfaceParams& params,
                           Interrupter* interrupter = nullptr);
// The same with the field's speed knobs (tests compare ways of planning; results agree).
struct MultilevelTuning;
SurfaceResult buildSurface(const SphereSet& spheres, const SurfaceParams& params,
                           Interrupter* interrupter, const MultilevelTuning& tuning);

// Where vertex normals come from: the field's gradient (Algorithm 1 line 8) either evaluated
// analytically at each vertex (exact near field plus the interpolated smooth levels), or by
// central differences at the stored voxels, interpolated trilinearly (the default: re-meshing
// then touches no sphere; normals agree within a fraction of a degree).
enum class NormalSource { Analytic, Grid };

// The iso-surface of an existing field at another iso-value (no field recomputation). Throws
// SurfaceRequestError when iso lies outside [isoMin, isoMax] (a rebuild is needed).
SurfaceMesh remesh(const SurfaceField& field, float iso, Interrupter* interrupter = nullptr,
                   NormalSource normals = NormalSource::Grid);

} // namespace faultline::core
