// GlRenderer, meshes: opaque ones drawn with the spheres, transparent ones merged into one mesh
// whose triangles are drawn back to front, re-sorted on the CPU only when the view changed.
#include "ui/render/gl_renderer.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>

namespace faultline::ui {

namespace {

constexpr int kVertexFloats = 10; // position, normal, colour with opacity

} // namespace

GlRenderer::GpuMesh GlRenderer::uploadMesh(std::span<const float> vertices,
                                           std::span<const std::uint32_t> indices,
                                           GLenum indexUsage) {
    GpuMesh g;
    g.vao = gl::makeVertexArray();
    g.vertices = gl::makeBuffer();
    g.indices = gl::makeBuffer();
    g.indexCount = static_cast<GLsizei>(indices.size());
    glBindVertexArray(g.vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, g.vertices.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size_bytes()), vertices.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size_bytes()),
                 indices.data(), indexUsage);
    const GLint sizes[3] = {3, 3, 4};
    for (GLuint a = 0, offset = 0; a < 3; offset += GLuint(sizes[a]), ++a) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(
            a, sizes[a], GL_FLOAT, GL_FALSE, kVertexFloats * sizeof(float),
            reinterpret_cast<const void*>(std::uintptr_t(offset * sizeof(float))));
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return g;
}

void GlRenderer::setMeshes(std::span<const MeshData> meshes) {
    m_meshes.clear();
    m_meshBounds = {};
    std::vector<float> interleaved;
    // The transparent meshes, merged.
    std::vector<float> clearVertices, clearPositions;
    std::vector<std::uint32_t> clearIndices;
    for (const MeshData& m : meshes) {
        assert(m.positions.size() % 3 == 0 && m.indices.size() % 3 == 0);
        const std::size_t n = m.positions.size() / 3;
        assert(m.normals.empty() || m.normals.size() == m.positions.size());
        assert(m.colors.empty() || m.colors.size() == m.positions.size());
        if (n == 0 || m.indices.empty())
            continue;
        const float opacity = std::clamp(m.opacity, 0.0f, 1.0f);
        interleaved.resize(n * kVertexFloats);
        glm::dvec3 lo(m.positions[0], m.positions[1], m.positions[2]), hi = lo;
        for (std::size_t v = 0; v < n; ++v) {
            float* out = &interleaved[kVertexFloats * v];
            for (int c = 0; c < 3; ++c) {
                out[c] = m.positions[3 * v + c];
                out[3 + c] = m.normals.empty() ? 0.0f : m.normals[3 * v + c];
                out[6 + c] = m.colors.empty() ? 0.7f : m.colors[3 * v + c];
            }
            out[9] = opacity;
            const glm::dvec3 p(out[0], out[1], out[2]);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        m_meshBounds = core::enclose(m_meshBounds, {(lo + hi) * 0.5, glm::length(hi - lo) * 0.5});
        if (opacity >= 1.0f) {
            m_meshes.push_back(uploadMesh(interleaved, m.indices, GL_STATIC_DRAW));
        } else if (opacity > 0.0f) {
            const auto base = static_cast<std::uint32_t>(clearPositions.size() / 3);
            clearVertices.insert(clearVertices.end(), interleaved.begin(), interleaved.end());
            clearPositions.insert(clearPositions.end(), m.positions.begin(), m.positions.end());
            for (std::uint32_t i : m.indices)
                clearIndices.push_back(base + i);
        }
    }
    m_transparent =
        clearIndices.empty() ? GpuMesh{} : uploadMesh(clearVertices, clearIndices, GL_DYNAMIC_DRAW);
    m_transparentOrder.setTriangles(clearPositions, clearIndices);
    ++m_stats.meshUploads;
}

void GlRenderer::useMeshProgram(const FrameSetup& f) {
    const GLuint p = m_programs.mesh.id();
    glUseProgram(p);
    gl::setMat4(p, "uView", f.view);
    gl::setMat4(p, "uProj", f.projection);
    glUniform1f(gl::uniformLocation(p, "uSpecular"), m_style.specular * 0.6f);
    glUniform1i(gl::uniformLocation(p, "uPerspective"), f.perspective ? 1 : 0);
}

void GlRenderer::drawOpaqueMeshes(const FrameSetup& f) {
    if (m_meshes.empty())
        return;
    useMeshProgram(f);
    for (const GpuMesh& m : m_meshes) {
        glBindVertexArray(m.vao.id());
        glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
        m_stats.meshTriangles += static_cast<std::size_t>(m.indexCount) / 3;
    }
    glBindVertexArray(m_emptyVao.id());
}

// Sorted triangles rather than a depth pre-pass (which blends only the nearest layer, so a
// fault behind another would vanish where they overlap) or per-pixel methods (weighted
// blending misjudges which layer is in front; depth peeling costs a pass per layer): fault
// surfaces are seen through each other, and the sort costs a fraction of a frame, once per
// camera move.
void GlRenderer::drawTransparentMeshes(const FrameSetup& f) {
    if (m_transparent.indexCount == 0)
        return;
    glBindVertexArray(m_transparent.vao.id());
    if (m_transparentOrder.update(f.eye, f.forward, f.perspective)) {
        const std::vector<std::uint32_t>& order = m_transparentOrder.indices();
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0,
                        static_cast<GLsizeiptr>(order.size() * sizeof(std::uint32_t)),
                        order.data());
        ++m_stats.meshSorts;
    }
    useMeshProgram(f);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDrawElements(GL_TRIANGLES, m_transparent.indexCount, GL_UNSIGNED_INT, nullptr);
    m_stats.meshTriangles += static_cast<std::size_t>(m_transparent.indexCount) / 3;
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindVertexArray(m_emptyVao.id());
}

} // namespace faultline::ui
