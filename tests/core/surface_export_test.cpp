// Surface exports read back: .vdb through OpenVDB's own reader, .glb through tinygltf.
#include "core/session/fault_surface_request.hpp"
#include "core/surface/detail/vdb_grids.hpp"
#include "core/surface/fault_surface.hpp"
#include "core/surface/surface_export.hpp"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

namespace fc = faultline::core;

namespace {

struct ExportSpheres {
    std::vector<float> x{0.0f, 0.8f, 1.6f}, y{0, 0, 0.2f}, z{0, 0.1f, 0}, r{0.5f, 0.5f, 0.4f};
    std::vector<float> rgb{1, 0, 0, 0, 1, 0, 0, 0, 1};
    fc::SphereSet set() const { return {x, y, z, r, rgb}; }
};

std::filesystem::path tempPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("faultline_surface_test_" + name);
}

// The test spheres' surface at `iso`, voxel 0.1 (r/d^2).
fc::SurfaceResult surfaceAt(const ExportSpheres& s, float iso) {
    fc::SurfaceParams params;
    params.iso = iso;
    params.voxelSize = 0.1f;
    return fc::buildSurface(s.set(), params);
}

} // namespace

TEST(SurfaceExport, VdbHoldsNamedGridsAndMetadata) {
    const ExportSpheres s;
    const auto result = surfaceAt(s, 2.0f);
    const auto path = tempPath("F1.vdb");
    const fc::VdbSurface entry{"F1", result.field.get(), 2.0f, {}};
    fc::exportVdb(path, {&entry, 1});

    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    auto grids = file.getGrids();
    file.close();
    ASSERT_EQ(grids->size(), 2u);
    auto density =
        openvdb::gridPtrCast<openvdb::FloatGrid>(openvdb::findGridByName(*grids, "F1.density"));
    auto color =
        openvdb::gridPtrCast<openvdb::Vec3SGrid>(openvdb::findGridByName(*grids, "F1.color"));
    ASSERT_TRUE(density) << (*grids)[0]->getName() << " " << (*grids)[0]->type();
    ASSERT_TRUE(color);
    EXPECT_EQ(density->getName(), "F1.density");
    EXPECT_EQ(color->getName(), "F1.color");
    EXPECT_FLOAT_EQ(density->metaValue<float>("iso"), 2.0f);
    EXPECT_EQ(density->metaValue<std::string>("kernel"), "inverse-square");
    EXPECT_FLOAT_EQ(density->metaValue<float>("voxel_size"), 0.1f);
    EXPECT_EQ(density->metaValue<std::int64_t>("sphere_count"), 3);
    EXPECT_EQ(color->metaValue<std::string>("faultline.fault"), "F1");
    EXPECT_DOUBLE_EQ(density->voxelSize()[0], 0.1f);
    EXPECT_EQ(density->activeVoxelCount(), result.field->stats().activeVoxels);
    std::filesystem::remove(path);
}

// A fault's VDB says what its colour grid's colours mean (the variable, map and range).
TEST(SurfaceExport, VdbSaysWhatTheColoursMean) {
    fc::Frame frame;
    for (int i = 0; i < 4; ++i) {
        frame.ids.push_back(i + 1);
        frame.x.push_back(0.8f * i), frame.y.push_back(0), frame.z.push_back(0);
        frame.radius.push_back(0.5f);
    }
    fc::AttributeColumn strain;
    strain.name = "strain";
    strain.floats = {0.0f, 0.1f, 0.2f, 0.3f};
    frame.attributes.push_back(strain);
    frame.finalize();
    fc::FaultSurfaceRequest request;
    request.fault.name = "F1";
    request.fault.ids = {1, 2, 3, 4};
    request.settings.fault = "F1";
    request.settings.kernel = faultline::core::MetaballKernel::Compact;
    request.settings.iso = 0.5;
    request.settings.colorBy = "strain";
    request.settings.colorMap = faultline::core::ColorMapSpec{faultline::core::ColorMapKind::Gray};
    request.settings.colorRange = std::array<double, 2>{0.0, 0.5};
    const auto path = tempPath("colours.vdb");
    fc::writeFaultVdb(frame, request, path.string());
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    auto grids = file.getGrids();
    file.close();
    auto color = openvdb::findGridByName(*grids, "F1.color");
    ASSERT_TRUE(color);
    EXPECT_EQ(color->metaValue<std::string>("color_by"), "strain");
    EXPECT_EQ(color->metaValue<std::string>("color_map"), "gray");
    EXPECT_EQ(color->metaValue<std::string>("color_range"), "0 0.5");
    EXPECT_FLOAT_EQ(color->metaValue<float>("color_reach"), 1.0f); // twice the mean radius
    std::filesystem::remove(path);
}

TEST(SurfaceExport, GlbHasOneNamedNodePerSurfaceAndGlyphsAsOneColouredMesh) {
    const ExportSpheres s;
    const auto a = surfaceAt(s, 2.0f);
    const auto b = surfaceAt(s, 2.5f);
    const fc::GltfSurface surfaces[] = {{"F1", &a.mesh}, {"F2", &b.mesh, 0.8}};
    const auto path = tempPath("faults.glb");
    fc::exportGlb(path, surfaces, s.set());

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) << err;
    ASSERT_EQ(model.nodes.size(), 3u);
    EXPECT_EQ(model.nodes[0].name, "F1");
    EXPECT_EQ(model.nodes[1].name, "F2");
    EXPECT_EQ(model.nodes[2].name, "glyphs");
    // z up (the model's) turned into glTF's y up by each node: -90 degrees about x.
    for (const auto& n : model.nodes) {
        ASSERT_EQ(n.rotation.size(), 4u);
        EXPECT_NEAR(n.rotation[0], -std::sqrt(0.5), 1e-9);
        EXPECT_NEAR(n.rotation[3], std::sqrt(0.5), 1e-9);
    }
    const auto& prim = model.meshes[model.nodes[0].mesh].primitives.at(0);
    for (const char* attr : {"POSITION", "NORMAL", "COLOR_0"})
        EXPECT_TRUE(prim.attributes.count(attr));
    EXPECT_EQ(model.accessors[prim.attributes.at("POSITION")].count, a.mesh.positions.size());
    EXPECT_EQ(model.accessors[prim.indices].count, a.mesh.indices.size());
    // Issue 41: an opaque surface is opaque; one at opacity 0.8 blends at 0.8, as in the views.
    const auto& opaque = model.materials.at(prim.material);
    EXPECT_EQ(opaque.alphaMode, "OPAQUE");
    const auto& seeThrough =
        model.materials.at(model.meshes[model.nodes[1].mesh].primitives.at(0).material);
    EXPECT_EQ(seeThrough.alphaMode, "BLEND");
    EXPECT_NEAR(seeThrough.pbrMetallicRoughness.baseColorFactor.at(3), 0.8, 1e-9);
    EXPECT_TRUE(seeThrough.doubleSided);
    EXPECT_EQ(model.materials.at(model.meshes[model.nodes[2].mesh].primitives.at(0).material).name,
              "glyph");
    // Issue 41, item 5: Blender 3.4 ignores EXT_mesh_gpu_instancing and showed one sphere. The
    // glyphs are one merged mesh: a 42-vertex sphere per exported sphere, in its colour.
    EXPECT_TRUE(model.nodes[2].extensions.empty());
    EXPECT_TRUE(model.extensionsUsed.empty());
    const auto& glyphs = model.meshes[model.nodes[2].mesh].primitives.at(0);
    ASSERT_TRUE(glyphs.attributes.count("COLOR_0"));
    const auto& positions = model.accessors[glyphs.attributes.at("POSITION")];
    EXPECT_EQ(positions.count, 3u * 42u);
    EXPECT_EQ(model.accessors[glyphs.indices].count, 3u * 80u * 3u);
    // Each sphere's vertices lie on it, in its colour: the second is green.
    const auto& colours = model.accessors[glyphs.attributes.at("COLOR_0")];
    const auto& view = model.bufferViews[colours.bufferView];
    const float* rgb = reinterpret_cast<const float*>(model.buffers[view.buffer].data.data() +
                                                      view.byteOffset + colours.byteOffset);
    for (std::size_t k = 42; k < 84; ++k) {
        EXPECT_EQ(rgb[3 * k], 0.0f);
        EXPECT_EQ(rgb[3 * k + 1], 1.0f);
    }
    const auto& pview = model.bufferViews[positions.bufferView];
    const float* xyz = reinterpret_cast<const float*>(model.buffers[pview.buffer].data.data() +
                                                      pview.byteOffset + positions.byteOffset);
    for (std::size_t k = 84; k < 126; ++k) // the third sphere: centre (1.6, 0.2, 0), radius 0.4
        EXPECT_NEAR(std::hypot(xyz[3 * k] - 1.6f, xyz[3 * k + 1] - 0.2f, xyz[3 * k + 2]), 0.4f,
                    1e-5f);
    std::filesystem::remove(path);
}

// A path ending in .gltf gets the JSON form (buffers embedded), which glTF tools read as text.
TEST(SurfaceExport, GltfPathWritesTheJsonForm) {
    const ExportSpheres s;
    const auto a = surfaceAt(s, 2.0f);
    const fc::GltfSurface surfaces[] = {{"F1", &a.mesh}};
    const auto path = tempPath("faults.gltf");
    fc::exportGlb(path, surfaces, s.set());
    std::ifstream in(path, std::ios::binary);
    char first = 0;
    in >> first;
    EXPECT_EQ(first, '{');
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, path.string())) << err;
    ASSERT_GE(model.nodes.size(), 1u);
    EXPECT_EQ(model.nodes[0].name, "F1");
    std::filesystem::remove(path);
}

// The mesh against the grids it was built from (the same grids export.vdb writes): each vertex's
// colour is the trilinear mean of its cell's stored corners' colours, and its normal comes from
// their central differences (one-sided beside a tile). Spheres scattered so that many leaves sit
// next to tiles, where the mesher reads the neighbourhood of each cell, voxel by voxel.
TEST(SurfaceGrids, VertexColoursAndNormalsComeFromTheStoredCorners) {
    ExportSpheres s{{}, {}, {}, {}, {}};
    std::mt19937 random(11);
    std::uniform_real_distribution<float> at(0.0f, 5.0f), radius(0.3f, 0.6f), unit(0.0f, 1.0f);
    for (int n = 0; n < 50; ++n) {
        s.x.push_back(at(random));
        s.y.push_back(at(random) * 0.4f);
        s.z.push_back(at(random));
        s.r.push_back(radius(random));
        s.rgb.insert(s.rgb.end(), {unit(random), unit(random), unit(random)});
    }
    fc::SurfaceParams params;
    params.iso = 10.0f;
    params.voxelSize = 0.09f;
    const auto built = fc::buildSurface(s.set(), params);
    const auto& grids = built.field->impl();
    const float h = built.field->voxelSize();
    auto density = grids.density->getConstAccessor();
    auto color = grids.color->getConstAccessor();
    const auto& mesh = built.mesh;
    ASSERT_GT(mesh.positions.size(), 2000u);
    std::size_t checked = 0, besideTiles = 0;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const auto& p = mesh.positions[v];
        openvdb::Coord cell;
        float t[3];
        bool onFace = false;
        for (int k = 0; k < 3; ++k) {
            const float u = p[k] / h;
            cell[k] = int(std::floor(u));
            t[k] = u - float(cell[k]);
            onFace = onFace || t[k] < 1e-3f || t[k] > 1.0f - 1e-3f; // which cell: ambiguous
        }
        if (onFace)
            continue;
        openvdb::Vec3d rgb(0.0), gradient(0.0);
        double weight = 0.0;
        bool tileNear = false;
        for (int c = 0; c < 8; ++c) {
            const openvdb::Coord corner = cell.offsetBy(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            if (!density.isValueOn(corner)) {
                tileNear = true;
                continue;
            }
            const double w = ((c & 1) ? t[0] : 1 - t[0]) * (((c >> 1) & 1) ? t[1] : 1 - t[1]) *
                             (((c >> 2) & 1) ? t[2] : 1 - t[2]);
            rgb += w * openvdb::Vec3d(color.getValue(corner));
            for (int a = 0; a < 3; ++a) {
                openvdb::Coord up = corner, down = corner;
                up[a] += 1, down[a] -= 1;
                const bool hasUp = density.isValueOn(up), hasDown = density.isValueOn(down);
                tileNear = tileNear || !hasUp || !hasDown;
                const double here = density.getValue(corner);
                gradient[a] +=
                    w * (hasUp && hasDown ? 0.5 * (density.getValue(up) - density.getValue(down))
                         : hasUp          ? density.getValue(up) - here
                         : hasDown        ? here - density.getValue(down)
                                          : 0.0);
            }
            weight += w;
        }
        if (weight <= 1e-3)
            continue;
        rgb /= weight;
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(mesh.colors[v][k], std::clamp(rgb[k], 0.0, 1.0), 2e-3)
                << "vertex " << v << " channel " << k;
        if (gradient.length() > 1e-3 * built.iso) {
            const openvdb::Vec3d n = -gradient / gradient.length();
            const auto& m = mesh.normals[v];
            EXPECT_GT(n[0] * m[0] + n[1] * m[1] + n[2] * m[2], 0.9999) << "vertex " << v;
        }
        ++checked;
        besideTiles += tileNear;
    }
    EXPECT_GT(checked, mesh.positions.size() / 2);
    // Both kinds of cells were looked at: whole neighbourhoods and ones beside tiles.
    EXPECT_GT(besideTiles, 100u);
    EXPECT_GT(checked - besideTiles, 1000u);
}
