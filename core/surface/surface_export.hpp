// Exporters for fault surfaces: .vdb (density + colour grids with metadata, for OpenVDB tools and
// Blender) and .glb (one named node per surface, optionally the glyphs as one merged mesh of
// spheres).
#pragma once

#include "core/surface/fault_surface.hpp"
#include "core/surface/sphere_set.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace faultline::core {

struct VdbSurface {
    std::string name; // the fault's name: grids "<name>.density" and "<name>.color"
    const SurfaceField* field = nullptr;
    float iso = 0.0f;
    // More string metadata on both grids (what the colour grid's colours mean).
    std::vector<std::pair<std::string, std::string>> notes;
};

// Writes the grids with metadata (faultline.fault, iso, kernel, voxel_size, sphere_count,
// tolerance, iso_min, iso_max, color_reach, and the notes). Throws std::runtime_error naming the
// path when writing fails.
void exportVdb(const std::filesystem::path& path, std::span<const VdbSurface> surfaces);

struct GltfSurface {
    std::string name; // node and mesh name
    const SurfaceMesh* mesh = nullptr;
    double opacity = 1.0; // under 1: its own material, alphaMode BLEND, base colour alpha
};

// Writes a binary glTF 2.0 file. Glyphs (may be empty) become one merged mesh node "glyphs": a
// small sphere per glyph (42 vertices, 12 past 20,000 glyphs) with its colour as COLOR_0, so any
// reader (Blender 3.4 too) shows one sphere per glyph in its colour. Throws std::runtime_error
// naming the path when writing fails.
void exportGlb(const std::filesystem::path& path, std::span<const GltfSurface> surfaces,
               const SphereSet& glyphs = {});

} // namespace faultline::core
