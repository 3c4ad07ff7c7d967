// Writes sample .glb files (surfaces, and surfaces with instanced glyphs) into a folder, for the
// glTF-Validator test. Usage: surface_export_samples OUTPUT_DIR
#include "core/surface/fault_surface.hpp"
#include "core/surface/surface_export.hpp"

#include <cstdio>
#include <filesystem>
#include <vector>

namespace fc = faultline::core;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: surface_export_samples OUTPUT_DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    std::vector<float> x, y, z, r, rgb;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 4; ++j) {
            x.push_back(0.9f * i);
            y.push_back(0.9f * j);
            z.push_back(0.3f * ((i + j) % 2));
            r.push_back(0.5f);
            rgb.insert(rgb.end(), {i / 5.0f, j / 3.0f, 0.5f});
        }
    const fc::SphereSet spheres{x, y, z, r, rgb};
    fc::SurfaceParams params;
    params.iso = 3.0f;
    params.voxelSize = 0.15f;
    params.colorReach = 0.5f;
    const auto a = fc::buildSurface(spheres, params);
    params.kernel = fc::MetaballKernel::Compact;
    params.iso = 0.3f;
    const auto b = fc::buildSurface(spheres, params);
    const fc::GltfSurface surfaces[] = {{"F1", &a.mesh}, {"F2 compact", &b.mesh}};
    fc::exportGlb(dir / "faults.glb", surfaces);
    fc::exportGlb(dir / "faults_glyphs.glb", surfaces, spheres);
    std::printf("wrote %zu + %zu triangles to %s\n", a.mesh.triangleCount(), b.mesh.triangleCount(),
                dir.string().c_str());
    return 0;
}
