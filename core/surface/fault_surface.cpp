#include "core/surface/fault_surface.hpp"

#include "core/surface/detail/field_level.hpp"
#include "core/surface/detail/surface_nets.hpp"
#include "core/surface/detail/vdb_grids.hpp"
#include "core/surface/metaball_reference.hpp"
#include "core/surface/surface_plan.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <unordered_map>

namespace faultline::core {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

// Stored densities are clamped here: above every supported iso-value, finite near centres.
float clampValue(float isoMax) { return 4.0f * isoMax; }

constexpr float kMaxColorReachRadii = 100.0f;

void validate(const SphereSet& s, const SurfaceParams& p) {
    if (s.size() == 0)
        throw SurfaceRequestError("cannot build a surface from an empty sphere set");
    if (!s.consistent())
        throw SurfaceRequestError("sphere columns differ in length (positions, radii, colours)");
    auto bad = [](float v) { return !std::isfinite(v); };
    if (!(p.iso > 0.0f) || bad(p.iso))
        throw SurfaceRequestError("iso-value must be a positive number, got " +
                                  std::to_string(p.iso));
    if (p.voxelSize < 0.0f || bad(p.voxelSize))
        throw SurfaceRequestError("voxel size must be positive (or 0 for radius / 3), got " +
                                  std::to_string(p.voxelSize));
    if (!(p.tolerance > 0.0f) || !(p.isoRangeFactor >= 1.0f) || !(p.compactReach > 0.0f) ||
        p.colorReach < 0.0f)
        throw SurfaceRequestError("tolerance, iso range, compact reach must be positive and the "
                                  "colour reach not negative");
    float largest = 0.0f;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (bad(s.x[i]) || bad(s.y[i]) || bad(s.z[i]) || !(s.radius[i] > 0.0f) || bad(s.radius[i]))
            throw SurfaceRequestError("sphere " + std::to_string(i) +
                                      " has a non-finite centre or a radius that is not positive");
        largest = std::max(largest, s.radius[i]);
    }
    // Beyond that every voxel would average nearly every sphere (and gather them all).
    if (bad(p.colorReach) || p.colorReach > kMaxColorReachRadii * largest)
        throw SurfaceRequestError("colour reach " + std::to_string(p.colorReach) + " is over " +
                                  std::to_string(static_cast<int>(kMaxColorReachRadii)) +
                                  " times the largest radius (" + std::to_string(largest) + ")");
}

enum class BlockSide { Below, Above, Crossing };

// Smallest and largest stored value of a block, and of each of its six faces (face 2 * axis for
// the layer at index 0 along the axis, 2 * axis + 1 for the layer at 7).
struct BlockRange {
    float lo, hi;
    float faceLo[6], faceHi[6];
};

// Taken while the block's values are still in cache. Eight lanes of running minima and maxima:
// no chain of dependent comparisons.
BlockRange blockRange(const float* v) {
    static_assert(kBlockDim == 8, "a row of z is eight lanes");
    BlockRange r;
    for (int f = 0; f < 6; ++f) {
        r.faceLo[f] = std::numeric_limits<float>::infinity();
        r.faceHi[f] = -std::numeric_limits<float>::infinity();
    }
    float lo[8], hi[8];
    for (int l = 0; l < 8; ++l)
        lo[l] = hi[l] = v[l];
    for (int i = 0; i < kBlockDim; ++i)
        for (int j = 0; j < kBlockDim; ++j) {
            const float* row = v + blockOffset(i, j, 0);
            float rowLo = row[0], rowHi = row[0];
            for (int l = 0; l < 8; ++l) {
                lo[l] = std::min(lo[l], row[l]);
                hi[l] = std::max(hi[l], row[l]);
                rowLo = std::min(rowLo, row[l]);
                rowHi = std::max(rowHi, row[l]);
            }
            auto face = [&](int f, float a, float b) {
                r.faceLo[f] = std::min(r.faceLo[f], a);
                r.faceHi[f] = std::max(r.faceHi[f], b);
            };
            if (i == 0)
                face(0, rowLo, rowHi);
            if (i == kBlockDim - 1)
                face(1, rowLo, rowHi);
            if (j == 0)
                face(2, rowLo, rowHi);
            if (j == kBlockDim - 1)
                face(3, rowLo, rowHi);
            face(4, row[0], row[0]);
            face(5, row[7], row[7]);
        }
    r.lo = lo[0], r.hi = hi[0];
    for (int l = 1; l < 8; ++l) {
        r.lo = std::min(r.lo, lo[l]);
        r.hi = std::max(r.hi, hi[l]);
    }
    return r;
}

// Which evaluated blocks hold, with the facing layers of their evaluated neighbours, only values
// on one side of [isoMin, isoMax]: no mesh edge for a supported iso touches them.
std::vector<BlockSide> blockSides(const std::vector<Coord3>& blocks,
                                  const std::vector<BlockRange>& ranges, float isoMin,
                                  float isoMax) {
    std::unordered_map<std::uint64_t, std::size_t> index;
    index.reserve(blocks.size());
    auto key = [](const Coord3& o) { return detail::packKey({o[0] >> 3, o[1] >> 3, o[2] >> 3}); };
    for (std::size_t b = 0; b < blocks.size(); ++b)
        index.emplace(key(blocks[b]), b);
    std::vector<BlockSide> sides(blocks.size(), BlockSide::Crossing);
    tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
        float lo = ranges[b].lo, hi = ranges[b].hi;
        for (int axis = 0; axis < 3; ++axis)
            for (int dir : {-1, 1}) {
                Coord3 o = blocks[b];
                o[axis] += dir * kBlockDim;
                auto it = index.find(key(o));
                if (it == index.end())
                    continue; // a tile: on this block's side by the plan's margin
                // The neighbour's layer that faces this block.
                const int face = 2 * axis + (dir < 0 ? 1 : 0);
                lo = std::min(lo, ranges[it->second].faceLo[face]);
                hi = std::max(hi, ranges[it->second].faceHi[face]);
            }
        sides[b] = hi < isoMin   ? BlockSide::Below
                   : lo > isoMax ? BlockSide::Above
                                 : BlockSide::Crossing;
    });
    return sides;
}

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
using ColorLeaf = openvdb::Vec3STree::LeafNodeType;

} // namespace

void ensureOpenVdbInitialized() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

SurfaceField::SurfaceField(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
SurfaceField::~SurfaceField() = default;
const SurfaceParams& SurfaceField::params() const { return m_impl->params; }
float SurfaceField::voxelSize() const { return m_impl->field->voxelSize(); }
std::size_t SurfaceField::sphereCount() const { return m_impl->field->sphereCount(); }
float SurfaceField::isoMin() const { return m_impl->isoMin; }
float SurfaceField::isoMax() const { return m_impl->isoMax; }
const SurfaceStats& SurfaceField::stats() const { return m_impl->stats; }
std::array<float, 2> SurfaceField::storedRange() const {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (auto it = m_impl->density->cbeginValueOn(); it; ++it) {
        lo = std::min(lo, *it);
        hi = std::max(hi, *it);
    }
    for (auto it = m_impl->density->cbeginValueOff(); it; ++it)
        if (it.isTileValue()) { // inside tiles: the clamp value
            lo = std::min(lo, *it);
            hi = std::max(hi, *it);
        }
    if (lo > hi)
        lo = hi = 0.0f;
    return {lo, hi};
}

float SurfaceField::maxAtCentres() const {
    const auto& s = m_impl->field->tree().spheres();
    const SphereSet set{s.x, s.y, s.z, s.r, {}};
    const std::size_t n = s.size(), samples = std::min<std::size_t>(n, 256);
    double most = 0.0;
    for (std::size_t q = 0; q < samples; ++q) {
        const std::size_t i = q * n / samples;
        most = std::max(most, referenceSample(set, m_impl->params, {s.x[i], s.y[i], s.z[i]}).value);
    }
    return static_cast<float>(most);
}

std::array<float, 2> SurfaceField::isoSliderRange() const {
    std::call_once(m_impl->sliderOnce, [this] {
        const auto& s = m_impl->field->tree().spheres();
        const auto r = core::isoSliderRange(SphereSet{s.x, s.y, s.z, s.r, {}}, m_impl->params);
        m_impl->slider = {static_cast<float>(r[0]), static_cast<float>(r[1])};
    });
    return m_impl->slider;
}

std::size_t SurfaceField::memoryBytes() const {
    return m_impl->density->memUsage() + m_impl->color->memUsage() +
           m_impl->stats.coarseNodes * sizeof(float) * 2 + sphereCount() * 7 * sizeof(float) +
           m_impl->field->gridBytes();
}

SurfaceResult buildSurface(const SphereSet& spheres, const SurfaceParams& params,
                           Interrupter* interrupter) {
    return buildSurface(spheres, params, interrupter, MultilevelTuning{});
}

SurfaceResult buildSurface(const SphereSet& spheres, const SurfaceParams& params,
                           Interrupter* interrupter, const MultilevelTuning& tuning) {
    validate(spheres, params);
    ensureOpenVdbInitialized();
    auto impl = std::make_unique<SurfaceField::Impl>();
    impl->params = params;
    impl->isoMin = params.iso / params.isoRangeFactor;
    impl->isoMax = params.iso * params.isoRangeFactor;
    const float h = resolvedVoxelSize(params, meanRadius(spheres));
    if (!(h > 0.0f))
        throw SurfaceRequestError("voxel size resolves to zero");

    auto t0 = Clock::now();
    impl->field = std::make_unique<MetaballField>(spheres, params, h, tuning);
    MetaballField& field = *impl->field;
    const SurfacePlan plan =
        planSurface(field, impl->isoMin, impl->isoMax, params.memoryBudgetBytes, interrupter);
    impl->stats.planSeconds = secondsSince(t0);

    // Field: coarse levels, then every planned block in parallel into its own leaves.
    t0 = Clock::now();
    if (interrupter)
        interrupter->start("field");
    field.prepare(plan.blocks, interrupter);
    impl->stats.levelsSeconds = secondsSince(t0);
    const auto tBlocks = Clock::now();
    std::vector<FloatLeaf*> densityLeaves(plan.blocks.size(), nullptr);
    std::vector<ColorLeaf*> colorLeaves(plan.blocks.size(), nullptr);
    std::vector<BlockRange> ranges(plan.blocks.size());
    const float clamp = clampValue(impl->isoMax);
    const openvdb::Vec3s initial(params.initialColor[0], params.initialColor[1],
                                 params.initialColor[2]);
    std::atomic<std::size_t> done{0};
    std::atomic<bool> cancelled{false};
    // A block's stored values, clamped, in a new leaf.
    auto storeBlock = [&](std::size_t b, float* density) {
        const auto& o = plan.blocks[b];
        auto* dl = new FloatLeaf(openvdb::Coord(o[0], o[1], o[2]), 0.0f, true);
        for (int n = 0; n < kBlockVoxels; ++n)
            density[n] = std::min(density[n], clamp);
        ranges[b] = blockRange(density);
        std::copy_n(density, kBlockVoxels, dl->buffer().data());
        densityLeaves[b] = dl;
    };
    // Blocks that bounds put wholly on one side of the iso range skip their near sums; their
    // ranges are those bounds. One of them is evaluated after all if a neighbour's facing layer
    // makes it part of the mesh.
    std::vector<char> skipped(plan.blocks.size(), 0);
    tbb::parallel_for(std::size_t{0}, plan.blocks.size(), [&](std::size_t b) {
        if (cancelled.load(std::memory_order_relaxed))
            return;
        float density[kBlockVoxels];
        FieldBounds bounds;
        if (field.evaluateBlockUnlessOneSided(plan.blocks[b], density, impl->isoMin, impl->isoMax,
                                              &bounds) != 0) {
            skipped[b] = 1;
            const float lo = std::min(static_cast<float>(bounds.low), clamp);
            const float hi = std::min(static_cast<float>(bounds.high), clamp);
            BlockRange& r = ranges[b];
            r.lo = lo, r.hi = hi;
            std::fill(std::begin(r.faceLo), std::end(r.faceLo), lo);
            std::fill(std::begin(r.faceHi), std::end(r.faceHi), hi);
        } else {
            storeBlock(b, density);
        }
        const std::size_t d = ++done;
        if (interrupter && (d & 63) == 0 &&
            interrupter->wasInterrupted(static_cast<int>(100 * d / plan.blocks.size())))
            cancelled = true;
    });
    if (cancelled) {
        for (auto* l : densityLeaves)
            delete l;
        for (auto* l : colorLeaves)
            delete l;
        throw SurfaceCancelled();
    }
    const auto transform = openvdb::math::Transform::createLinearTransform(h);
    impl->density = openvdb::FloatGrid::create(0.0f);
    impl->density->setTransform(transform);
    impl->color = openvdb::Vec3SGrid::create(initial);
    impl->color->setTransform(transform->copy());
    for (const auto& [lo, hi] : plan.inside)
        impl->density->tree().sparseFill(openvdb::CoordBBox(openvdb::Coord(lo[0], lo[1], lo[2]),
                                                            openvdb::Coord(hi[0], hi[1], hi[2])),
                                         clamp, false);
    const std::vector<BlockSide> sides =
        blockSides(plan.blocks, ranges, impl->isoMin, impl->isoMax);
    // A skipped block next to values on the other side of an iso holds mesh corners: evaluate it.
    // (Its neighbours were judged by its bounds, which lie on the same side as its values: a
    // neighbour that is wholly on one side stays so, at worst one is kept as crossing.)
    tbb::parallel_for(std::size_t{0}, plan.blocks.size(), [&](std::size_t b) {
        if (!skipped[b] || sides[b] != BlockSide::Crossing)
            return;
        float density[kBlockVoxels];
        field.evaluateBlock(plan.blocks[b], density, nullptr);
        storeBlock(b, density);
    });
    impl->stats.blocksSeconds = secondsSince(tBlocks);
    const auto tColor = Clock::now();
    // Colour (Figure 4) only where the mesh can be: the blocks that keep their voxels.
    tbb::parallel_for(std::size_t{0}, plan.blocks.size(), [&](std::size_t b) {
        if (sides[b] != BlockSide::Crossing)
            return;
        const auto& o = plan.blocks[b];
        Vec3f color[kBlockVoxels];
        field.evaluateColor(o, color);
        auto* cl = new ColorLeaf(openvdb::Coord(o[0], o[1], o[2]), initial, true);
        openvdb::Vec3s* out = cl->buffer().data();
        for (int n = 0; n < kBlockVoxels; ++n)
            out[n] = openvdb::Vec3s(color[n][0], color[n][1], color[n][2]);
        colorLeaves[b] = cl;
    });
    impl->stats.colorSeconds = secondsSince(tColor);
    for (std::size_t b = 0; b < plan.blocks.size(); ++b) {
        if (sides[b] == BlockSide::Crossing) {
            impl->density->tree().addLeaf(densityLeaves[b]);
            impl->color->tree().addLeaf(colorLeaves[b]);
            continue;
        }
        // No edge of this block or into it can cross any supported iso: a tile will do.
        if (sides[b] == BlockSide::Above)
            impl->density->tree().addTile(
                1, openvdb::Coord(plan.blocks[b][0], plan.blocks[b][1], plan.blocks[b][2]), clamp,
                false);
        delete densityLeaves[b];
    }
    impl->stats.fieldSeconds = secondsSince(t0);
    impl->stats.blocks = plan.blocks.size();
    impl->stats.activeVoxels = impl->density->activeVoxelCount();
    impl->stats.coarseNodes = field.coarseNodeCount();
    impl->stats.levels = field.levelCount();
    impl->stats.anterpolatedLevels = field.anterpolatedLevels();
    impl->stats.nearCutoff = field.nearCutoff();
    impl->stats.kappa = field.kappa();
    impl->stats.estimatedError = field.estimatedError();
    if (interrupter)
        interrupter->end();

    SurfaceResult result;
    result.iso = params.iso;
    auto shared = std::make_shared<SurfaceField>(std::move(impl));
    t0 = Clock::now();
    result.mesh = remesh(*shared, params.iso, interrupter);
    const_cast<SurfaceStats&>(shared->stats()).meshSeconds = secondsSince(t0);
    result.field = std::move(shared);
    return result;
}

SurfaceMesh remesh(const SurfaceField& surface, float iso, Interrupter* interrupter,
                   NormalSource normalSource) {
    if (!surface.supportsIso(iso))
        throw SurfaceRequestError("iso-value " + std::to_string(iso) + " is outside [" +
                                  std::to_string(surface.isoMin()) + ", " +
                                  std::to_string(surface.isoMax()) +
                                  "] that this surface's grid holds; rebuild the surface");
    const auto& impl = surface.impl();
    if (interrupter)
        interrupter->start("mesh");
    SurfaceMesh mesh;
    const bool analytic = normalSource == NormalSource::Analytic;
    detail::surfaceNets(*impl.density, *impl.color, !analytic, iso, surface.voxelSize(), mesh);
    if (interrupter && interrupter->wasInterrupted(50))
        throw SurfaceCancelled();
    if (analytic) {
        std::vector<Vec3f> gradients(mesh.positions.size());
        impl.field->evaluatePoints(mesh.positions, nullptr, gradients.data());
        mesh.normals.resize(gradients.size());
        tbb::parallel_for(std::size_t{0}, gradients.size(), [&](std::size_t i) {
            mesh.normals[i] = detail::normalFromGradient(gradients[i]);
        });
    }
    // The mesher winds counter-clockwise from outside; a sample of triangles against the normals
    // confirms it (and would flip a mesh whose normals all point the other way).
    double agreement = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3 * 17) {
        const auto& a = mesh.positions[mesh.indices[t]];
        const auto& b = mesh.positions[mesh.indices[t + 1]];
        const auto& c = mesh.positions[mesh.indices[t + 2]];
        const Vec3f u{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
            v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const Vec3f n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                      u[0] * v[1] - u[1] * v[0]};
        const auto& m = mesh.normals[mesh.indices[t]];
        agreement += n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
    }
    if (agreement < 0.0)
        tbb::parallel_for(std::size_t{0}, mesh.indices.size() / 3, [&](std::size_t t) {
            std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
        });
    if (interrupter)
        interrupter->end();
    return mesh;
}

} // namespace faultline::core
