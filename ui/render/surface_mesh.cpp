#include "ui/render/surface_mesh.hpp"

namespace faultline::ui {

MeshData toMeshData(const core::SurfaceMesh& mesh) {
    MeshData out;
    out.positions.reserve(mesh.positions.size() * 3);
    for (const auto& p : mesh.positions)
        out.positions.insert(out.positions.end(), p.begin(), p.end());
    out.normals.reserve(mesh.normals.size() * 3);
    for (const auto& n : mesh.normals)
        out.normals.insert(out.normals.end(), n.begin(), n.end());
    out.colors.reserve(mesh.colors.size() * 3);
    for (const auto& c : mesh.colors)
        out.colors.insert(out.colors.end(), c.begin(), c.end());
    out.indices = mesh.indices;
    return out;
}

} // namespace faultline::ui
