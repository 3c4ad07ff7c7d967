// Picking: which visible sphere a mouse ray hits first. A uniform grid over the visible spheres
// (built once per frame/visibility change, in O(n)) is walked cell by cell along the ray.
#pragma once

#include "core/view/geometry.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace faultline::core {

struct SphereHit {
    std::size_t row = 0;
    double t = 0.0;        // distance along the ray
    glm::dvec3 point{0.0}; // where the ray meets the sphere
};

class SpherePicker {
  public:
    // Indexes the spheres whose mask byte is non-zero (all when mask is empty). The spans must
    // stay alive until the next build().
    void build(std::span<const float> x, std::span<const float> y, std::span<const float> z,
               std::span<const float> radius, std::span<const std::uint8_t> mask = {});

    // The nearest sphere the ray enters at t >= 0 (a ray starting inside a sphere hits it at 0).
    std::optional<SphereHit> pick(const Ray& ray) const;

    std::size_t indexedCount() const { return m_count; }
    glm::ivec3 gridSize() const { return m_dims; }

  private:
    std::span<const float> m_x, m_y, m_z, m_r;
    std::size_t m_count = 0;
    glm::dvec3 m_lo{0.0}, m_hi{0.0};
    glm::dvec3 m_cell{1.0};
    glm::ivec3 m_dims{0, 0, 0};
    std::vector<std::uint32_t>
        m_cellStart; // CSR: rows of cell c are m_rows[start[c] .. start[c+1])
    std::vector<std::uint32_t> m_rows;

    std::size_t cellIndex(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * m_dims.y + j) * m_dims.x + i;
    }
};

} // namespace faultline::core
