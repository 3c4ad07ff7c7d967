// GlViewRenderer: the workbench's views drawn by the sphere renderer (ui/render), one renderer
// per view so each keeps its frame on the GPU. Only what changed is re-sent (positions when the
// frame changes, the visible list when the mask changes, a small texture for the colour map),
// and a view whose scene did not change is not drawn again.
#pragma once

#include "ui/render/renderer.hpp"
#include "ui/viewport/view_renderer.hpp"

#include <map>
#include <memory>
#include <string>

namespace faultline::ui {

// The renderer's camera for a session camera (azimuth/elevation orbit, +z up).
core::Camera toRenderCamera(const core::CameraState& camera);

class GlViewRenderer final : public ViewRenderer {
  public:
    // Needs a current OpenGL 4.1+ context; `backend` Mock for tests without one.
    explicit GlViewRenderer(RendererBackend backend = RendererBackend::OpenGL);
    ~GlViewRenderer() override;

    void render(const ViewScene& scene) override;
    unsigned int texture(const std::string& view) const override;
    void forget(const std::string& view) override;
    std::string description() const override { return m_description; }
    bool drawsBoxes() const override { return true; }

    // The renderer of a view (tests).
    Renderer* rendererOf(const std::string& view) const;
    // How many times views were actually drawn (skipped when nothing changed).
    std::size_t drawCount() const { return m_draws; }

  private:
    struct Slot {
        std::unique_ptr<Renderer> renderer;
        std::shared_ptr<const core::Frame> frame;
        std::string variable = "\x01"; // what the values were made from
        std::shared_ptr<const core::AttributeColumn> column;
        std::vector<std::pair<std::shared_ptr<const MeshData>, float>> surfaceKey;
        std::uint64_t visibleKey = ~0ull;
        std::string signature;     // everything else that changes the picture
        std::vector<float> values; // integer columns converted once per frame
    };
    RendererBackend m_backend;
    std::map<std::string, Slot> m_slots;
    std::string m_description;
    std::size_t m_draws = 0;
};

} // namespace faultline::ui
