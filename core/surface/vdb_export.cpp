#include "core/surface/detail/vdb_grids.hpp"
#include "core/surface/surface_export.hpp"

#include <openvdb/io/File.h>
#include <tbb/task_arena.h>

#include <stdexcept>

namespace faultline::core {

void exportVdb(const std::filesystem::path& path, std::span<const VdbSurface> surfaces) {
    ensureOpenVdbInitialized();
    openvdb::GridPtrVec grids;
    for (const auto& s : surfaces) {
        if (!s.field)
            throw std::invalid_argument("exportVdb: surface '" + s.name + "' has no field");
        const auto& impl = s.field->impl();
        auto density = impl.density->copyGrid(); // shares the tree; own name and metadata
        auto color = impl.color->copyGrid();
        density->setName(s.name + ".density");
        color->setName(s.name + ".color");
        for (auto& grid : {density, color}) {
            grid->insertMeta("faultline.fault", openvdb::StringMetadata(s.name));
            grid->insertMeta("iso", openvdb::FloatMetadata(s.iso));
            grid->insertMeta("kernel",
                             openvdb::StringMetadata(std::string(kernelName(impl.params.kernel))));
            grid->insertMeta("voxel_size", openvdb::FloatMetadata(s.field->voxelSize()));
            grid->insertMeta("sphere_count", openvdb::Int64Metadata(static_cast<std::int64_t>(
                                                 s.field->sphereCount())));
            grid->insertMeta("tolerance", openvdb::FloatMetadata(impl.params.tolerance));
            grid->insertMeta("iso_min", openvdb::FloatMetadata(s.field->isoMin()));
            grid->insertMeta("iso_max", openvdb::FloatMetadata(s.field->isoMax()));
            grid->insertMeta("color_reach", openvdb::FloatMetadata(impl.params.colorReach));
            for (const auto& [key, value] : s.notes)
                grid->insertMeta(key, openvdb::StringMetadata(value));
            grid->setSaveFloatAsHalf(false);
            grids.push_back(grid);
        }
        density->setGridClass(openvdb::GRID_UNKNOWN);
    }
    openvdb::MetaMap fileMeta;
    fileMeta.insertMeta("creator", openvdb::StringMetadata("Faultline"));
    try {
        openvdb::io::File file(path.string());
        // On the calling thread alone: the write's only parallel part is OpenVDB's pass for the
        // grids' statistics metadata (milliseconds). Run by TBB's workers from inside Debian's
        // uninstrumented libopenvdb, its waits on our stack are invisible to ThreadSanitizer and
        // the caller's next use of that stack is reported as a race.
        tbb::task_arena callerOnly(1, 1);
        callerOnly.execute([&] {
            file.write(grids, fileMeta);
            file.close();
        });
    } catch (const openvdb::Exception& e) {
        throw std::runtime_error(path.string() + ": cannot write VDB file: " + e.what());
    }
}

} // namespace faultline::core
