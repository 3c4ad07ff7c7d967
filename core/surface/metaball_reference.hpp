// The paper's Algorithm 1 taken literally: every sphere against every point, no cutoff.
// It is the exact reference the fast multilevel field is tested and benchmarked against.
#pragma once

#include "core/surface/sphere_set.hpp"
#include "core/surface/surface_params.hpp"

#include <array>
#include <vector>

namespace faultline::core {

struct FieldSample {
    double value = 0.0;
    std::array<double, 3> gradient{0, 0, 0}; // Algorithm 1 line 8: the analytic gradient of the sum
    std::array<float, 3> color{1, 1, 1};     // Figure 4
};

double meanRadius(const SphereSet& spheres);

// Field, gradient and colour at one point, in double precision.
FieldSample referenceSample(const SphereSet& spheres, const SurfaceParams& params,
                            const std::array<double, 3>& point);

// An iso-value whose surface wraps the spheres closely: over a sample of the spheres, the field
// 1.5 radii from the centre on the side where it is lowest (outwards, for spheres at the edge of
// the set); the lower quartile of those, so that most of the spheres are inside. The kernels'
// values grow with the number of spheres (the tails add up), so no fixed default iso suits
// every fault; with the long-tailed inverse kernel the surface is rounder and looser than with
// inverse-square. Sums every sphere for each sample point: about 600 x N kernel evaluations.
double wrappingIso(const SphereSet& spheres, const SurfaceParams& params);

// The iso-values worth offering on a slider for these spheres, [low, high]: `high` is where the
// surface has shrunk into the spheres (over a sample of them, the largest field half a radius
// from a centre, on the side where it is lowest: above it every sampled sphere's surface is
// gone or nearly); `low` a third of the wrapping iso (a loose hull well outside the spheres).
// About 1,200 x N kernel evaluations.
std::array<double, 2> isoSliderRange(const SphereSet& spheres, const SurfaceParams& params);

// Field on a dense box of voxels [origin, origin + dims) (world = index * voxelSize), x fastest;
// every sphere against every voxel, in parallel. What the benchmark compares against. With
// `gradient`, also the analytic gradient at every voxel (Algorithm 1 line 8), in the same order.
std::vector<float> algorithm1Dense(const SphereSet& spheres, const SurfaceParams& params,
                                   const std::array<int, 3>& origin, const std::array<int, 3>& dims,
                                   float voxelSize,
                                   std::vector<std::array<float, 3>>* gradient = nullptr);

} // namespace faultline::core
