#include "core/surface/surface_export.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

namespace faultline::core {

namespace {

// Vertices stay in the model's coordinates (z up, as DEM codes write them); each node turns
// them -90 degrees about x into glTF's y-up frame, so Blender, three.js and other viewers stand
// the model upright (issue 41 walkthrough: faults.glb loaded on its side). Quaternion x, y, z, w.
const std::vector<double> kZUpToYUp{-0.70710678118654752, 0.0, 0.0, 0.70710678118654752};

using V3 = std::array<float, 3>;

// Appends raw data to the single buffer, 4-byte aligned; returns the new buffer view's index.
int addView(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
    auto& buffer = model.buffers.front().data;
    while (buffer.size() % 4)
        buffer.push_back(0);
    const std::size_t offset = buffer.size();
    buffer.resize(offset + bytes);
    std::memcpy(buffer.data() + offset, data, bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    if (target)
        view.target = target;
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
}

int addVec3Accessor(tinygltf::Model& model, const std::vector<V3>& values, bool withBounds,
                    int target = TINYGLTF_TARGET_ARRAY_BUFFER) {
    tinygltf::Accessor a;
    a.bufferView = addView(model, values.data(), values.size() * sizeof(V3), target);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = values.size();
    if (withBounds) {
        V3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
              std::numeric_limits<float>::max()};
        V3 hi{-lo[0], -lo[1], -lo[2]};
        for (const auto& v : values)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], v[k]);
                hi[k] = std::max(hi[k], v[k]);
            }
        a.minValues = {lo[0], lo[1], lo[2]};
        a.maxValues = {hi[0], hi[1], hi[2]};
    }
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
}

int addIndexAccessor(tinygltf::Model& model, const std::vector<std::uint32_t>& indices) {
    tinygltf::Accessor a;
    a.bufferView = addView(model, indices.data(), indices.size() * sizeof(std::uint32_t),
                           TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = indices.size();
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
}

int addMesh(tinygltf::Model& model, const std::string& name, const std::vector<V3>& positions,
            const std::vector<V3>& normals, const std::vector<V3>* colors,
            const std::vector<std::uint32_t>& indices, int material) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = addVec3Accessor(model, positions, true);
    prim.attributes["NORMAL"] = addVec3Accessor(model, normals, false);
    if (colors)
        prim.attributes["COLOR_0"] = addVec3Accessor(model, *colors, false);
    prim.indices = addIndexAccessor(model, indices);
    prim.material = material;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    return static_cast<int>(model.meshes.size()) - 1;
}

// Unit icosphere (one subdivision of an icosahedron: 42 vertices, 80 triangles).
void icosphere(std::vector<V3>& v, std::vector<std::uint32_t>& tri) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
           4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
           6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    auto normalize = [](V3 p) {
        const float l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        return V3{p[0] / l, p[1] / l, p[2] / l};
    };
    for (auto& p : v)
        p = normalize(p);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        const auto key = std::minmax(a, b);
        auto it = mid.find(key);
        if (it != mid.end())
            return it->second;
        v.push_back(
            normalize({(v[a][0] + v[b][0]) / 2, (v[a][1] + v[b][1]) / 2, (v[a][2] + v[b][2]) / 2}));
        const auto index = static_cast<std::uint32_t>(v.size() - 1);
        mid.emplace(key, index);
        return index;
    };
    std::vector<std::uint32_t> finer;
    for (std::size_t i = 0; i < tri.size(); i += 3) {
        const std::uint32_t a = tri[i], b = tri[i + 1], c = tri[i + 2];
        const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri = std::move(finer);
}

} // namespace

void exportGlb(const std::filesystem::path& path, std::span<const GltfSurface> surfaces,
               const SphereSet& glyphs) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "Faultline";
    model.buffers.emplace_back();
    tinygltf::Material material; // vertex colours times white, double-sided surfaces
    material.name = "fault-surface";
    material.doubleSided = true;
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    int opaqueMaterial = -1; // added when a surface needs it (an unused one is a validator note)
    tinygltf::Scene scene;
    scene.name = "faults";
    for (const auto& s : surfaces) {
        if (!s.mesh)
            throw std::invalid_argument("exportGlb: surface '" + s.name + "' has no mesh");
        tinygltf::Node node;
        node.name = s.name;
        node.rotation = kZUpToYUp;
        if (s.mesh->triangleCount() > 0) {
            int materialIndex = opaqueMaterial;
            if (s.opacity >= 1.0 && opaqueMaterial < 0) {
                model.materials.push_back(material);
                materialIndex = opaqueMaterial = static_cast<int>(model.materials.size()) - 1;
            } else if (s.opacity < 1.0) {
                // A see-through surface, as the workbench draws it (issue 41): glTF readers
                // (Blender, three.js) blend by the base colour's alpha.
                tinygltf::Material seeThrough = material;
                seeThrough.name = "fault-surface-" + s.name;
                seeThrough.alphaMode = "BLEND";
                seeThrough.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0,
                                                                   std::clamp(s.opacity, 0.0, 1.0)};
                model.materials.push_back(seeThrough);
                materialIndex = static_cast<int>(model.materials.size()) - 1;
            }
            node.mesh = addMesh(model, s.name, s.mesh->positions, s.mesh->normals, &s.mesh->colors,
                                s.mesh->indices, materialIndex);
        }
        model.nodes.push_back(node);
        scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
    }
    if (glyphs.size() > 0) {
        // One merged mesh, a small sphere per glyph with its colour at each vertex: every glTF
        // reader shows it (Blender 3.4 drops EXT_mesh_gpu_instancing and imported one sphere).
        // A coarser sphere past 20,000 glyphs keeps big exports in hand (12 vertices, not 42).
        std::vector<V3> sphere;
        std::vector<std::uint32_t> tri;
        icosphere(sphere, tri);
        if (glyphs.size() > 20000) {
            sphere.resize(12);
            tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                   4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                   6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
        }
        const std::size_t nv = sphere.size(), n = glyphs.size();
        if (n * nv > std::numeric_limits<std::uint32_t>::max())
            throw std::runtime_error(path.string() + ": too many spheres for one glTF mesh");
        std::vector<V3> positions(n * nv), normals(n * nv), colors(n * nv);
        std::vector<std::uint32_t> indices(n * tri.size());
        for (std::size_t i = 0; i < n; ++i) {
            const float r = glyphs.radius[i];
            const V3 c = glyphs.rgb.empty()
                             ? V3{1, 1, 1}
                             : V3{glyphs.rgb[3 * i], glyphs.rgb[3 * i + 1], glyphs.rgb[3 * i + 2]};
            for (std::size_t k = 0; k < nv; ++k) {
                positions[i * nv + k] = {glyphs.x[i] + r * sphere[k][0],
                                         glyphs.y[i] + r * sphere[k][1],
                                         glyphs.z[i] + r * sphere[k][2]};
                normals[i * nv + k] = sphere[k];
                colors[i * nv + k] = c;
            }
            for (std::size_t t = 0; t < tri.size(); ++t)
                indices[i * tri.size() + t] = static_cast<std::uint32_t>(i * nv + tri[t]);
        }
        tinygltf::Material glyphMaterial; // vertex colours times white
        glyphMaterial.name = "glyph";
        glyphMaterial.pbrMetallicRoughness.metallicFactor = 0.0;
        glyphMaterial.pbrMetallicRoughness.roughnessFactor = 0.6;
        model.materials.push_back(glyphMaterial);
        tinygltf::Node node;
        node.name = "glyphs";
        node.rotation = kZUpToYUp;
        node.mesh = addMesh(model, "glyphs", positions, normals, &colors, indices,
                            static_cast<int>(model.materials.size()) - 1);
        model.nodes.push_back(node);
        scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
    }
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    tinygltf::TinyGLTF writer;
    // .gltf: JSON with the buffers embedded; anything else a binary .glb.
    const bool binary = path.extension() != ".gltf";
    if (!writer.WriteGltfSceneToFile(&model, path.string(), false, true, !binary, binary))
        throw std::runtime_error(path.string() + ": cannot write glTF file");
}

} // namespace faultline::core
