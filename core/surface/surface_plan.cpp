#include "core/surface/surface_plan.hpp"

#include "core/surface/detail/plan_fold.hpp"
#include "core/surface/metaball_reference.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace faultline::core {

std::string formatBytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 5) {
        bytes /= 1024.0;
        ++u;
    }
    char text[64];
    std::snprintf(text, sizeof text, "%.1f %s", bytes, units[u]);
    return text;
}

namespace {

struct Cell {
    Coord3 origin; // in blocks
    int size;      // in blocks, a power of two
    // Inverse kernels: the index of the parent's Fold in the level's folds.
    std::int32_t fold = 0;
};

// World box of a cell's voxels, with one voxel of margin (see planSurface()).
detail::Box cellBox(const Cell& cell, float h) {
    detail::Box b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = static_cast<float>(cell.origin[k] * kBlockDim - 1) * h;
        b.hi[k] = static_cast<float>((cell.origin[k] + cell.size) * kBlockDim) * h;
    }
    return b;
}

enum class CellClass { Outside, Inside, Straddle };

std::string formatNumber(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

// A refusal that says what would fit: a voxel size a user would pick (up to the largest
// radius: coarser voxels no longer resolve the spheres), else, when the iso-value lies far
// below the one that wraps the spheres (so the surface is a huge loose shell), that iso-value.
[[noreturn]] void refuseBudget(const MetaballField& field, double neededBytes, std::size_t budget,
                               const char* how, double shellDistance = 0.0) {
    const float voxel = field.voxelSize();
    const SurfaceParams& params = field.params();
    std::string text = "surface needs " + std::string(how) + " " + formatBytes(neededBytes) +
                       " at voxel size " + formatNumber(voxel) + " but the budget is " +
                       formatBytes(static_cast<double>(budget));
    std::vector<std::string> fits;
    const double fitVoxel = voxel * std::sqrt(neededBytes / static_cast<double>(budget));
    if (fitVoxel <= field.maxRadius())
        fits.push_back("a voxel size of at least " + formatNumber(fitVoxel * 1.05));
    if (params.kernel != MetaballKernel::Compact) {
        const auto& s = field.tree().spheres();
        const double wrap = wrappingIso(SphereSet{s.x, s.y, s.z, s.r, {}}, params);
        if (params.iso < wrap / 1.5) {
            std::string why = "the iso-value that wraps the spheres, about " + formatNumber(wrap) +
                              " (\"iso\":\"wrap\"): " + formatNumber(params.iso) +
                              " lies far below the field";
            if (shellDistance > 0.0)
                why += ", so the surface would be a shell about " + formatNumber(shellDistance) +
                       " units out";
            fits.push_back(why);
        }
    }
    if (fits.empty())
        fits.push_back("fewer spheres, or a larger memory budget");
    text += "; use ";
    for (std::size_t i = 0; i < fits.size(); ++i)
        text += (i ? ", or " : "") + fits[i];
    throw SurfaceRequestError(text);
}

// Inverse kernels: a lower bound on the blocks the surface needs, before any planning. Within
// R_in = (W / isoMax)^(1/p) - ext of the spheres' weighted centre (ext: the farthest centre from
// it, W: the total weight) every sphere is within (W / isoMax)^(1/p), so f > isoMax there: the
// surface encloses that ball and meets every ray from its centre beyond R_in. A block at least
// R_in away covers a solid angle of at most (sqrt(3) b)^2 pi / 4 / R_in^2 (b: its side), so at
// least 16 R_in^2 / (3 b^2) blocks hold it. R_in: 0 when there is no such ball.
double enclosedBallRadius(const MetaballField& field, float isoMax) {
    if (field.params().kernel == MetaballKernel::Compact)
        return 0.0;
    const auto& s = field.tree().spheres();
    double c[3] = {0, 0, 0}, w = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        c[0] += double(s.r[i]) * s.x[i], c[1] += double(s.r[i]) * s.y[i];
        c[2] += double(s.r[i]) * s.z[i], w += s.r[i];
    }
    if (!(w > 0.0))
        return 0.0;
    double ext2 = 0.0;
    for (int k = 0; k < 3; ++k)
        c[k] /= w;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double dx = s.x[i] - c[0], dy = s.y[i] - c[1], dz = s.z[i] - c[2];
        ext2 = std::max(ext2, dx * dx + dy * dy + dz * dz);
    }
    const double ratio = field.totalWeight() / isoMax;
    const double reach =
        field.params().kernel == MetaballKernel::Inverse ? ratio : std::sqrt(ratio);
    return std::max(0.0, reach - std::sqrt(ext2));
}

} // namespace

SurfacePlan planSurface(const MetaballField& field, float isoMin, float isoMax,
                        std::size_t budgetBytes, Interrupter* interrupter) {
    SurfacePlan plan;
    plan.isoMin = isoMin;
    plan.isoMax = isoMax;
    const float h = field.voxelSize();
    const double reach = field.reach(isoMin) + field.maxRadius();
    const auto& box = field.centreBox();
    const double blockWorld = kBlockDim * static_cast<double>(h);
    // A surface far out around the spheres (an iso-value far below theirs) is refused at once.
    if (const double inner = enclosedBallRadius(field, isoMax); inner > 0.0) {
        const double side = blockWorld, margin = std::sqrt(3.0) * side;
        const double r = std::max(0.0, inner - margin);
        const double blocks = 16.0 * r * r / (3.0 * side * side);
        if (blocks * kBytesPerBlock > static_cast<double>(budgetBytes))
            refuseBudget(field, blocks * kBytesPerBlock, budgetBytes, "at least", inner);
    }

    Coord3 lo, hi;
    int extent = 1;
    for (int k = 0; k < 3; ++k) {
        const double l = std::floor((box.lo[k] - reach) / blockWorld);
        const double u = std::floor((box.hi[k] + reach) / blockWorld);
        // OpenVDB and our keys hold voxel indices within +-2^20.
        if (std::abs(l) * kBlockDim > (1 << 20) - 64 || std::abs(u) * kBlockDim > (1 << 20) - 64)
            throw SurfaceRequestError(
                "surface region (" + std::to_string(static_cast<long long>((u - l) * blockWorld)) +
                " world units across) is too large for voxel size " + std::to_string(h) +
                "; raise the voxel size or the iso-value");
        lo[k] = static_cast<int>(l);
        hi[k] = static_cast<int>(u);
        while (extent < hi[k] - lo[k] + 1)
            extent *= 2;
    }
    const std::size_t budgetBlocks = std::max<std::size_t>(1, budgetBytes / kBytesPerBlock);
    int levelsLeft = 0;
    for (int s = extent; s > 1; s /= 2)
        ++levelsLeft;

    std::vector<Cell> cells{{lo, extent, 0}};
    // Inverse kernels: folds (see detail::Fold) instead of the tree's bounds, for sparse and
    // dense sets alike. Issue 40: dense sets (a thick zone in which every sphere is selected)
    // were planned with the tree, whose bounds of r/d open node after node for the far spheres
    // at every cell and then give up, keeping cells the surface does not cross: on the demo's
    // 29,936 spheres at r/3, 1.26 s and 67k blocks by the tree against 0.16 s and 31k blocks by
    // folds. A fold's near list of a dense set holds a few hundred spheres per block.
    const MetaballKernel kernel = field.params().kernel;
    const bool folding = kernel != MetaballKernel::Compact && field.tuning().foldPlanning;
    const int power = kernel == MetaballKernel::Inverse ? 1 : 2;
    const float minD2 = field.inverseKernel().minD2;
    std::vector<detail::Fold> folds(1), childFolds;
    if (folding) {
        const auto& s = field.tree().spheres();
        folds[0].x = s.x, folds[0].y = s.y, folds[0].z = s.z, folds[0].r = s.r;
    }
    if (interrupter)
        interrupter->start("plan");
    while (!cells.empty()) {
        std::vector<CellClass> classes(cells.size());
        if (folding)
            childFolds.assign(cells.size(), detail::Fold{});
        tbb::parallel_for(std::size_t{0}, cells.size(), [&](std::size_t c) {
            const Cell& cell = cells[c];
            if (folding) {
                const detail::Box box = cellBox(cell, h);
                const FieldBounds b = detail::foldBounds(folds[cell.fold], box, power, minD2);
                classes[c] = b.high < isoMin  ? CellClass::Outside
                             : b.low > isoMax ? CellClass::Inside
                                              : CellClass::Straddle;
                if (classes[c] == CellClass::Straddle && cell.size > 1)
                    childFolds[c] = detail::foldFor(folds[cell.fold], box, power, minD2);
                return;
            }
            // One voxel of margin: a voxel next to an evaluated block is then on the same side
            // of every supported iso as the tile it lies in, so every mesh edge that crosses
            // the surface joins two evaluated voxels.
            Coord3 vlo, vhi;
            for (int k = 0; k < 3; ++k) {
                vlo[k] = cell.origin[k] * kBlockDim - 1;
                vhi[k] = (cell.origin[k] + cell.size) * kBlockDim;
            }
            const FieldBounds b = field.bounds(vlo, vhi, isoMin, isoMax, field.tuning().maxOpen);
            classes[c] = b.high < isoMin  ? CellClass::Outside
                         : b.low > isoMax ? CellClass::Inside
                                          : CellClass::Straddle;
        });
        std::vector<Cell> next;
        std::size_t straddling = 0;
        for (std::size_t c = 0; c < cells.size(); ++c) {
            const Cell& cell = cells[c];
            if (classes[c] == CellClass::Outside)
                continue;
            if (classes[c] == CellClass::Inside) {
                Coord3 vlo, vhi;
                for (int k = 0; k < 3; ++k) {
                    vlo[k] = cell.origin[k] * kBlockDim;
                    vhi[k] = (cell.origin[k] + cell.size) * kBlockDim - 1;
                }
                plan.inside.emplace_back(vlo, vhi);
                continue;
            }
            ++straddling;
            if (cell.size == 1) {
                plan.blocks.push_back(cell.origin);
                continue;
            }
            const int half = cell.size / 2;
            for (int child = 0; child < 8; ++child) {
                const Coord3 o{cell.origin[0] + (child & 1) * half,
                               cell.origin[1] + ((child >> 1) & 1) * half,
                               cell.origin[2] + ((child >> 2) & 1) * half};
                if (o[0] > hi[0] || o[1] > hi[1] || o[2] > hi[2])
                    continue;
                next.push_back({o, half, static_cast<std::int32_t>(c)});
            }
        }
        // Every straddling cell holds at least one straddling block (almost always), so a level
        // with more straddling cells than the budget allows is refused at once; a surface's
        // block count grows about 4x per halving, which gives the estimate.
        if (straddling > budgetBlocks) {
            const double estimate = static_cast<double>(straddling) *
                                    std::pow(4.0, std::max(levelsLeft, 0)) * kBytesPerBlock;
            refuseBudget(field, estimate, budgetBytes, "about");
        }
        --levelsLeft;
        cells = std::move(next);
        if (folding)
            folds.swap(childFolds);
        if (interrupter && interrupter->wasInterrupted(-1))
            throw SurfaceCancelled();
    }
    for (auto& b : plan.blocks)
        for (int k = 0; k < 3; ++k)
            b[k] *= kBlockDim;
    plan.estimatedBytes =
        plan.blocks.size() * kBytesPerBlock + field.sphereCount() * 48 + field.gridBytes();
    if (interrupter)
        interrupter->end();
    return plan;
}

} // namespace faultline::core
