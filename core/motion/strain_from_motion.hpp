// Strain from motion: per-sphere deformation between a reference frame and the current one,
// from how each sphere's neighbourhood moved (spheres matched by id). The contract is the
// journal's (shared/design/JOURNAL.md, "Strain from motion"), as OVITO's Atomic Strain:
//   neighbours of sphere i: the spheres within `cutoff` of it in the reference frame;
//   X, Y: a neighbour's vector then and now (minimum image on the boxes' periodic axes);
//   F = (sum Y X^T)(sum X X^T)^-1, E = (F^T F - I) / 2;
//   shear_strain = sqrt(Exy^2 + Eyz^2 + Exz^2 + ((Exx-Eyy)^2 + (Eyy-Ezz)^2 + (Ezz-Exx)^2) / 6),
//   volumetric_strain = (Exx + Eyy + Ezz) / 3, d2min = sum |Y - F X|^2,
//   displacement = |x - x_ref|.
// 2-D data (every reference centre shares one coordinate) uses the in-plane 2 x 2 form, as OVITO
// does: shear = sqrt(Exy^2 + (Exx-Eyy)^2 / 2), volumetric = (Exx + Eyy) / 2.
// NaN: a sphere whose id is not in the reference; a centre that is not a finite number in either
// frame (such a sphere is no one's neighbour either); fewer than 3 neighbours (that are also in
// the current frame); a singular sum X X^T.
// Cost: one cell list of the reference (ghost images on periodic axes), then per cell the ~130
// points of the 27 cells around it kept to the ~65 within the cutoff of its spheres' box, and
// each sphere's ~20 neighbours among those, in parallel (TBB). About 0.25 us of CPU a sphere
// (2.8 GHz Ice Lake, AVX2, 525k spheres, rows shuffled); see bench_strain. Scratch memory
// comes from the scratch pool (core/util/scratch_array.hpp), reused from frame to frame.
#pragma once

#include "core/model/frame.hpp"

#include <string>
#include <vector>

namespace faultline::core {

// 1.5 x the median diameter of the reference; when the file gave no radius, 1.5 x the spacing a
// random close packing of the same number of spheres in the centres' bounds would have.
double defaultStrainCutoff(const Frame& reference);
// 1.5 x that packing's spacing, whatever the radii (what to suggest when they are far off).
double packingStrainCutoff(const Frame& reference);
// About how many other spheres lie within `cutoff` of each, from the density of the centres in
// their bounds (at most all of them; outliers that widen the bounds make it an underestimate).
double strainNeighboursWithin(const Frame& reference, double cutoff);
// strain.add refuses an automatic cutoff that takes in more spheres around each than this (a
// packing's takes about 17, at 1.5 diameters; this many lie within about 5 diameters).
inline constexpr double kMaxAutomaticStrainNeighbours = 2000;
// And one that takes in fewer than this (radii a tenth of the spacing or less: a packing's 17 x
// 0.1^3). Outliers that widen the centres' bounds lower the estimate: a sandbox whose fallen
// grains made its bounds ten times taller still reads 1.7.
inline constexpr double kMinAutomaticStrainNeighbours = 0.05;

// The seven columns (kStrainVariables order, each named prefix + variable) for every row of
// `now`. `cutoff` <= 0: defaultStrainCutoff(reference). Results do not depend on thread count.
std::vector<AttributeColumn> strainFromMotion(const Frame& now, const Frame& reference,
                                              double cutoff, const std::string& prefix = {});

// The same columns, all NaN (no reference frame for this frame).
std::vector<AttributeColumn> strainUnavailable(const Frame& now, const std::string& prefix = {});

namespace detail {
// The neighbour sums have an AVX2 form, used where the CPU has AVX2 and FMA, and a baseline
// one. true: the baseline everywhere (tests compare the two; benchmarks time them).
void setStrainBaselineOnly(bool baselineOnly);
// Whether strainFromMotion takes the AVX2 sums now (the CPU has them, not set to the baseline).
bool strainUsesAvx2();
// Where the CPU has AVX-512 (F, DQ, BW, VL), the AVX2 sums take it: the same values to the last
// bit. false: AVX2 only (tests compare the two; benchmarks time them).
void setStrainAvx512Allowed(bool allowed);
bool strainUsesAvx512();
} // namespace detail

} // namespace faultline::core
