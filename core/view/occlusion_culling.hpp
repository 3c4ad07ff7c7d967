// Occlusion culling of spheres for renderers without early depth rejection (CPU rasterisers such
// as Mesa llvmpipe shade every fragment of a depth-writing impostor). Draw likely occluders
// first, read back their depth, and drop every sphere whose whole screen footprint lies behind it.
// It is conservative: the final image equals drawing every sphere.
#pragma once

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace faultline::core {

// How the spheres are seen: world-to-view and projection matrices (OpenGL conventions, default
// depth range [0, 1]) and the target size in pixels.
struct SphereProjection {
    glm::dmat4 view{1.0};
    glm::dmat4 projection{1.0};
    int width = 1;
    int height = 1;
    bool perspective = true;
};

// Screen footprint of one sphere: inclusive pixel rectangle (clipped to the target) and the
// smallest window depth any of its points can have.
struct SphereFootprint {
    std::uint32_t row = 0;
    float nearDepth = 0.0f;
    std::uint16_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool crossesNear = false; // pokes through the near plane: never culled, never an occluder
};

// Footprint of a sphere, or false when it is entirely outside the view (off-screen, behind the
// near plane, beyond the far plane). Pixel rows count up from the bottom, as glReadPixels gives.
bool projectSphere(const SphereProjection& p, const glm::dvec3& centre, double radius,
                   SphereFootprint& out);

class SphereOcclusionCuller {
  public:
    // Projects the candidate rows; spheres outside the view are dropped now (frustum culling).
    void begin(std::span<const float> x, std::span<const float> y, std::span<const float> z,
               std::span<const float> radius, std::span<const std::uint32_t> rows,
               const SphereProjection& projection);

    // The nearest candidate per tile of tileSize x tileSize pixels (by the centre of its
    // footprint), removed from the candidates. Empty when no candidate is left. A tile size of 0
    // picks one from the candidates' footprints (about one front sphere per tile).
    std::vector<std::uint32_t> takeOccluders(int tileSize);

    // Drops every candidate whose footprint lies entirely behind `depth`: window depths of the
    // target (width * height floats, bottom row first) after the occluders were drawn.
    void cullBehind(std::span<const float> depth);

    // The candidates still standing (to draw last); the culler is empty afterwards.
    std::vector<std::uint32_t> takeRemaining();

    std::size_t candidateCount() const { return m_candidates.size(); }
    std::size_t frustumCulled() const { return m_frustumCulled; }
    std::size_t occlusionCulled() const { return m_occlusionCulled; }

  private:
    SphereProjection m_projection;
    std::vector<SphereFootprint> m_candidates;
    std::size_t m_frustumCulled = 0;
    std::size_t m_occlusionCulled = 0;
    // Max-depth pyramid: level 0 is the depth buffer itself, level k halves each side.
    std::vector<std::vector<float>> m_levels;
    std::vector<glm::ivec2> m_levelSize;
    void buildPyramid(std::span<const float> depth);
    int autoTileSize() const;
    float maxDepthOver(const SphereFootprint& f, std::span<const float> level0) const;
};

} // namespace faultline::core
