// Back-to-front order of transparent triangles for one view, so blending with "over" composites
// every layer in the right order. Sorts (a linear-time radix sort) only when the view changed.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace faultline::core {

class TriangleDepthOrder {
  public:
    // Triangles as vertex indices (three each) into positions (x y z per vertex). Forgets the
    // previous order: the next update sorts.
    void setTriangles(std::span<const float> positions, std::span<const std::uint32_t> indices);

    // Sorts the triangles farthest first, by the distance of their centroids from the eye
    // (perspective) or along the view direction (orthographic, where only that direction
    // matters). Returns true when it sorted, false when the order for this view is kept.
    bool update(const glm::dvec3& eye, const glm::dvec3& forward, bool perspective);

    // The triangles' vertex indices in the current order (three per triangle).
    const std::vector<std::uint32_t>& indices() const { return m_sorted; }
    std::size_t triangleCount() const { return m_centroids.size() / 3; }
    std::uint64_t sorts() const { return m_sorts; }

  private:
    std::vector<float> m_centroids; // x y z per triangle
    std::vector<std::uint32_t> m_indices, m_sorted;
    std::vector<std::uint32_t> m_keys, m_order, m_keysTmp, m_orderTmp;
    bool m_valid = false;
    bool m_perspective = true;
    glm::dvec3 m_eye{0.0}, m_forward{0.0};
    std::uint64_t m_sorts = 0;
};

} // namespace faultline::core
