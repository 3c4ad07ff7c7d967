// The Mock back end: keeps the scene like the OpenGL one and records every upload and draw it
// would make, so viewport logic and tests run with no display.
#pragma once

#include "ui/render/renderer.hpp"

#include <string>
#include <vector>

namespace faultline::ui {

struct MockCall {
    std::string what;      // "upload.positions", "draw.spheres", "draw.legend", ...
    std::size_t count = 0; // rows, bytes or primitives, as fits the call
    bool operator==(const MockCall&) const = default;
};

class MockRenderer final : public Renderer {
  public:
    RendererBackend backend() const override { return RendererBackend::Mock; }
    void setSpheres(const SphereColumns& spheres) override;
    void setSphereValues(std::span<const float> values) override;
    void setVisibleMask(std::span<const std::uint8_t> mask) override;
    void setColorMap(const core::ColorMapSpec& map) override;
    void setColorRange(core::ValueRange range) override;
    void setMeshes(std::span<const MeshData> meshes) override;
    void setBoxes(std::span<const BoxOverlay> boxes,
                  std::optional<BoxHandlesOverlay> selected) override;
    void setStyle(const RenderStyle& style) override;
    void render(const core::Camera& camera, const RenderTarget& target) override;
    RgbaImage readImage() override;
    unsigned int colorTexture() const override { return 0; }
    const RenderStats& stats() const override { return m_stats; }
    core::BoundingSphere sceneBounds() const override;

    const std::vector<MockCall>& calls() const { return m_calls; }
    void clearCalls() { m_calls.clear(); }
    // The last render's draw calls only (a suffix of calls()).
    std::vector<MockCall> lastFrame() const;
    const std::vector<std::uint32_t>& visibleRows() const { return m_visible; }
    core::ValueRange colorRange() const { return m_range; }
    const core::ColorMapSpec& colorMap() const { return m_map; }

  private:
    std::vector<MockCall> m_calls;
    std::size_t m_frameStart = 0;
    RenderStats m_stats;
    RenderStyle m_style;
    std::vector<float> m_x, m_y, m_z, m_r;
    bool m_hasValues = false;
    std::vector<std::uint32_t> m_visible, m_hidden;
    core::ColorMapSpec m_map;
    core::ValueRange m_range;
    std::size_t m_meshTriangles = 0;
    std::size_t m_meshCount = 0;
    core::BoundingSphere m_meshBounds;
    std::vector<BoxOverlay> m_boxes;
    std::optional<BoxHandlesOverlay> m_selected;
    RenderTarget m_lastTarget{0, 0};

    void record(std::string what, std::size_t count) {
        m_calls.push_back({std::move(what), count});
    }
};

} // namespace faultline::ui
