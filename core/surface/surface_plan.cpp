#include "core/surface/surface_plan.hpp"

#include "core/surface/detail/plan_fold.hpp"

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

[[noreturn]] void refuseBudget(double neededBytes, std::size_t budget, float voxel,
                               const char* how) {
    const double scale = std::sqrt(neededBytes / static_cast<double>(budget));
    char text[160];
    std::snprintf(text, sizeof text, "use a voxel size of at least %.3g", voxel * scale);
    throw SurfaceRequestError("surface needs " + std::string(how) + " " + formatBytes(neededBytes) +
                              " at voxel size " + std::to_string(voxel) + " but the budget is " +
                              formatBytes(static_cast<double>(budget)) + "; " + text);
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
    // Sparse sets with inverse kernels: folds (see detail::Fold) instead of the tree's bounds.
    const MetaballKernel kernel = field.params().kernel;
    // Dense sets keep the tree: within a few cells of any cell lie thousands of spheres, which
    // folds would list one by one.
    const bool folding = kernel != MetaballKernel::Compact && field.sparse();
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
            refuseBudget(estimate, budgetBytes, h, "about");
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
    plan.estimatedBytes = plan.blocks.size() * kBytesPerBlock + field.sphereCount() * 48;
    if (interrupter)
        interrupter->end();
    return plan;
}

} // namespace faultline::core
