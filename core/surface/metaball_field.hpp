// MetaballField: the paper's field (eq. 1) evaluated fast on sparse voxel blocks by multilevel
// summation: exact near field within a cutoff a0, smooth remainders on ever coarser grids.
#pragma once

#include "core/surface/detail/sphere_grid.hpp"
#include "core/surface/detail/sphere_tree.hpp"
#include "core/surface/interrupter.hpp"
#include "core/surface/metaball_kernel.hpp"
#include "core/surface/sphere_set.hpp"
#include "core/surface/surface_params.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace faultline::core {

using Coord3 = std::array<int, 3>;
using Vec3f = std::array<float, 3>;

// A block is 8^3 voxels (an OpenVDB leaf); voxel (i, j, k) sits at world (i, j, k) * voxelSize.
inline constexpr int kBlockDim = 8;
inline constexpr int kBlockVoxels = kBlockDim * kBlockDim * kBlockDim;
// Offset of a voxel in a block's arrays: z fastest, as in an OpenVDB leaf.
inline int blockOffset(int i, int j, int k) { return (i * kBlockDim + j) * kBlockDim + k; }

struct FieldBounds {
    double low = 0.0;
    double high = 0.0;
};

namespace detail {
struct FieldLevel;
struct Brick;
struct ChargeGrid;
struct WindowList;
} // namespace detail

// Knobs that trade speed between the levels; they do not change the accuracy target.
struct MultilevelTuning {
    double nearCutoffRadii = 3.0; // exact near field within about this many mean radii
    double topLevelPairs = 2.0e7; // stop coarsening once the top sum costs at most this
    bool topByCost = true;        // also stop once the top sum costs less than going on
    int kappa = 0;                // near cutoff / level-1 spacing; 0: chosen with coarseKappa
    int softeningOrder = 4;       // gamma_a is C^order
    int coarseKappa = 0;          // cutoff / spacing on levels >= 2; 0: the cheapest pair
                                  // (kappa, coarseKappa) whose error estimate fits the budget
    int minRatio = 2;             // level-1 spacing at least this many voxels
    int anterpolateFrom = 3;      // levels from this one up may sum grid charges instead of
                                  // spheres (multilevel summation's anterpolation) where the
                                  // error budget has room for it; 0: never
    double chargeShare = 0.9;     // ... and where the charges number at most this many spheres
    // For sparse sets (see MetaballField::sparse()) the near cutoff is this much wider: it costs
    // little there (few spheres in it) and saves level-1 nodes, which would outnumber the voxels'
    // sums. 1: never wider.
    double sparseNearFactor = 5.0 / 3.0;
    // ... and level 1 at least this many voxels apart: its nodes' window sums, not the few
    // near spheres, are what a sparse set's field costs (bench_surface's spread-out cases).
    int sparseMinRatio = 4;
    bool foldPlanning = true; // inverse kernels plan by folds; false: by the tree's bounds
                              // as the compact kernel does (tests compare the two)
    int maxOpen = 256;        // planning: tree nodes opened per block bound
    int probeOpen = 40;       // planning: after this many openings, give up on a bound
    double giveUpRatio = 2.0; // whose high is over ratio * isoMin and low under isoMax / ratio
};

namespace detail {
// Guaranteed bounds of sum_i r_i / max(d_i, minD)^power (power 1 or 2) over a box, each sphere
// from its nearest and farthest point of the box, 8 spheres at a time; added to low and high.
void addDirectBounds(int power, const float* x, const float* y, const float* z, const float* r,
                     std::size_t count, const Box& box, float minD2, double& low, double& high);
} // namespace detail

class MetaballField {
  public:
    // Copies the spheres into its own tree order, and again by grid cell (the caller's columns
    // may go away later).
    MetaballField(const SphereSet& spheres, const SurfaceParams& params, float voxelSize,
                  const MultilevelTuning& tuning = {});
    ~MetaballField();
    MetaballField(const MetaballField&) = delete;
    MetaballField& operator=(const MetaballField&) = delete;

    float voxelSize() const { return m_h; }
    const MultilevelTuning& tuning() const { return m_tuning; }
    const SurfaceParams& params() const { return m_params; }
    // Inverse kernels: whether the median sphere has under 8 mean radii of weight within 3 mean
    // radii (touching spheres have about 20), as in a strain-threshold selection spread over a
    // block. Sparse sets take a wider near cutoff and a coarser level 1.
    bool sparse() const { return m_sparse; }
    // The inverse kernels' power and the squared distance below which they are clamped.
    const InverseKernel& inverseKernel() const { return m_kernel; }
    std::size_t sphereCount() const { return m_tree.spheres().size(); }
    const detail::SphereTree& tree() const { return m_tree; }
    // Memory of the spheres' grid (the near and colour lists' index).
    std::size_t gridBytes() const { return m_grid.memoryBytes(); }
    // Sum of all weights, bounding box of the centres, and largest radius.
    double totalWeight() const { return m_tree.root().weight; }
    const detail::Box& centreBox() const { return m_tree.root().box; }
    float maxRadius() const { return m_tree.root().rmax; }
    // Beyond this distance from the centre box, f < iso everywhere.
    double reach(double iso) const;

    // Guaranteed bounds of f over the voxel-index box [lo, hi] (inclusive), tightened by opening
    // at most maxOpen tree nodes, and no further once they decide [isoMin, isoMax] either way.
    FieldBounds bounds(const Coord3& lo, const Coord3& hi, double isoMin, double isoMax,
                       int maxOpen = 64) const;

    // Computes the coarse levels the given blocks need (block origins are multiples of 8).
    // Must be called once before evaluateBlock / evaluatePoints.
    void prepare(std::span<const Coord3> blockOrigins, Interrupter* interrupter);

    // Density and colour of the 512 voxels of a prepared block (blockOffset order).
    // color may be null: density only (colour later, for the blocks that keep it).
    void evaluateBlock(const Coord3& origin, float* density, Vec3f* color) const;
    // Density of a prepared block, unless bounds (the coarse levels' part exactly, each near
    // sphere's range over the block) put all of it below isoMin (returns -1) or above isoMax
    // (returns 1): then only `bounds` is set, and density holds nothing. Returns 0 when the
    // density was evaluated. Saves the near sums of blocks next to the surface that it misses.
    int evaluateBlockUnlessOneSided(const Coord3& origin, float* density, float isoMin,
                                    float isoMax, FieldBounds* bounds) const;
    // Figure 4 colour of the 512 voxels of a block (needs no prepare()).
    void evaluateColor(const Coord3& origin, Vec3f* color) const;

    // Value and analytic gradient at points inside or next to prepared blocks.
    void evaluatePoints(std::span<const Vec3f> points, float* values, Vec3f* gradients) const;

    // Cutoff of the exact near field and the number of coarse levels (for reports and tests).
    // The constructor chooses the cutoffs by an estimate that assumes coarse levels up to twice
    // the spheres' span; prepare() may then choose cheaper ones that fit the budget with the
    // levels the blocks actually need.
    float nearCutoff() const { return m_a0; }
    int kappa() const { return m_kappa; }
    int coarseKappa() const { return m_coarseKappa; }
    // A priori estimate of the largest |f - f_exact| (from kErrorPerScale and errorScale()): the
    // one the cutoffs were chosen by, then after prepare() that of the levels it built (with
    // their grid charges).
    double estimatedError() const { return m_estimatedError; }
    // That estimate in two parts: level 1's interpolation ([0]) and the coarser levels' ([1],
    // with their grid charges' share).
    std::array<double, 2> estimatedErrorParts() const;
    // The densest weight within each level's cutoff over cutoff^p: the size of what level 1
    // ([0]) and the coarser levels ([1]) interpolate.
    // memo: densest weight per cutoff, shared between calls for several kappas.
    // terms: each cutoff's own term, [l] for a_l.
    // Stops early (a partial sum) once weights . scale exceeds stopAbove.
    std::array<double, 2>
    errorScale(std::map<double, double>* memo = nullptr, std::vector<double>* terms = nullptr,
               const std::array<double, 2>& weights = {0.0, 0.0},
               double stopAbove = std::numeric_limits<double>::infinity()) const;
    // Cutoff a_l: level 0 sums k - gamma_{a_0} exactly; level l >= 1 sums gamma_{a_{l-1}} -
    // gamma_{a_l} within a_l on a grid of spacing ratio * voxel * 2^(l-1).
    double cutoff(int level) const;
    double weightWithin(const Vec3f& point, double radius) const;
    int levelCount() const { return static_cast<int>(m_levels.size()); }
    // How many of the coarsest levels sum grid charges instead of spheres (after prepare()).
    int anterpolatedLevels() const { return m_anterpolated; }
    std::size_t coarseNodeCount() const;

  private:
    // A pair of cutoffs (kappa, coarse kappa) at a level-1 spacing of ratio voxels, with the
    // work model's cost and (once estimated) the error estimate.
    struct CutoffChoice {
        int kappa = 0, coarse = 0, ratio = 0;
        double error = 0.0, cost = 0.0;
    };
    void applyChoice(const CutoffChoice& choice);
    // Whether the median sphere has few neighbours (see sparse()).
    bool isSparse() const;
    // Marks the nodes of levels 1 .. top the blocks need (m_levels, without values).
    void planLevels(std::span<const Coord3> blockOrigins);
    // The a priori estimate for the planned levels: level 1's term and each coarser level's.
    double levelsEstimate() const;
    // errorScale()'s term of cutoff a_l for the chosen cutoffs (non-empty m_errorTerms).
    double errorTerm(int l) const;
    // The steps of prepare(), in order (metaball_field_levels.cpp).
    void indexBlocks(std::span<const Coord3> blocks);
    void chooseCutoffsFor(std::span<const Coord3> blocks);
    std::vector<std::optional<detail::ChargeGrid>> chooseChargeLevels();
    void computeLevels(const std::vector<std::optional<detail::ChargeGrid>>& charges,
                       Interrupter* interrupter);
    void sumWindows(const detail::FieldLevel& level, detail::Brick& brick,
                    const detail::ChargeGrid* grid, const detail::WindowList& topCharges) const;
    // The spheres within the near cutoff of a block, and the block's near sums from them.
    void gatherNear(const Coord3& origin, detail::NearList& list) const;
    void nearValues(const Coord3& origin, const detail::NearList& list, float* density) const;
    void sumNear(const detail::NearList& list, const Vec3f& p, float& value, Vec3f* gradient,
                 Vec3f* color) const;

    detail::SphereTree m_tree;
    detail::SphereGrid m_grid; // the same spheres by block-sized cells: near and colour lists
    SurfaceParams m_params;
    MultilevelTuning m_tuning;
    float m_h;
    double m_meanRadius = 0.0;
    InverseKernel m_kernel;
    float m_a0 = 0.0f; // near cutoff
    int m_kappa = 0;
    bool m_sparse = false;
    int m_coarseKappa = 0;
    double m_estimatedError = 0.0;
    std::vector<double> m_errorTerms;    // errorScale()'s terms for the chosen cutoffs
    std::map<double, double> m_densest;  // cutoff -> densest weight within it (errorScale memo)
    std::vector<CutoffChoice> m_cheaper; // cheaper than the constructor's choice, cheapest first
    int m_ratio1 = 1;                    // level-1 spacing in voxels
    SoftenedKernel m_soft0;              // gamma_a0
    std::vector<std::unique_ptr<detail::FieldLevel>> m_levels; // level 1 .. L
    // While prepare() tries cutoffs: the levels marked above the last try's top, the level-1
    // ratio they were marked for, and the squared span their nodes and the centres cover.
    std::vector<std::unique_ptr<detail::FieldLevel>> m_spareLevels;
    int m_markedRatio = 0;
    double m_span2 = 0.0;
    int m_anterpolated = 0;
    std::unordered_map<std::uint64_t, std::uint32_t> m_blocks; // prepared block -> index
    std::vector<Coord3> m_blockOrigins;
};

} // namespace faultline::core
