// The OpenGL back end: sphere impostors pulled from buffer textures by a compact list of visible
// rows, meshes, box edges and handles, screen-space contact darkening, supersampling, and a
// colour-bar legend; optional occlusion culling for software rasterisers; transparent surfaces
// sorted back to front.
#pragma once

#include "core/view/occlusion_culling.hpp"
#include "core/view/triangle_depth_order.hpp"
#include "ui/render/gl_resources.hpp"
#include "ui/render/renderer.hpp"
#include "ui/render/text_atlas.hpp"

#include <map>
#include <memory>

namespace faultline::ui {

class GlRenderer final : public Renderer {
  public:
    // Needs a current OpenGL 4.1+ context; throws std::runtime_error otherwise or when a
    // shader does not build.
    GlRenderer();
    ~GlRenderer() override;

    RendererBackend backend() const override { return RendererBackend::OpenGL; }
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
    unsigned int colorTexture() const override { return m_output.color(); }
    const RenderStats& stats() const override { return m_stats; }
    core::BoundingSphere sceneBounds() const override;

    // True on Mesa llvmpipe/softpipe and similar (OcclusionCulling::Auto turns culling on).
    bool softwareRenderer() const { return m_software; }
    const std::string& rendererName() const { return m_rendererName; }

  private:
    struct Programs {
        gl::Program spheresPerspective, spheresOrthographic, points, mesh, lines, occlusion,
            composite, downsample, overlay;
    };
    // Vertices interleave position, normal (zero: flat shading) and colour with opacity.
    struct GpuMesh {
        gl::VertexArray vao;
        gl::Buffer vertices, indices;
        GLsizei indexCount = 0;
    };
    struct FontTexture {
        FontAtlas atlas;
        gl::Texture texture;
    };
    // Per-frame matrices and sizes.
    struct FrameSetup {
        glm::dmat4 view{1.0}, projection{1.0};
        glm::dvec3 eye{0.0}, forward{0.0, 0.0, -1.0}; // world space
        core::ClipRange clip;
        bool perspective = true;
        int width = 0, height = 0; // of the pass being drawn
        int supersample = 1;
    };

    Programs m_programs;
    RenderStats m_stats;
    RenderStyle m_style;
    bool m_software = false;
    std::string m_rendererName;

    // Spheres: CPU copies (culling, bounds) and their GPU forms.
    std::vector<float> m_x, m_y, m_z, m_r;
    core::BoundingSphere m_sphereBounds;
    double m_typicalRadius = 1.0;
    gl::BufferTexture m_spheresTex; // RGBA32F x y z r
    gl::BufferTexture m_valuesTex;  // R32F
    bool m_hasValues = false;
    std::vector<std::uint32_t> m_visible, m_hidden;
    gl::BufferTexture m_visibleTex, m_hiddenTex, m_passRowsTex; // R32UI
    core::SphereOcclusionCuller m_culler;
    std::vector<float> m_depth;

    gl::Texture m_colorMapTex;
    core::ColorMapSpec m_map;
    int m_bandCount = 0;
    core::ValueRange m_range;

    std::vector<GpuMesh> m_meshes; // opaque, one per mesh
    // Every transparent mesh in one, so triangles of different meshes sort among each other;
    // its index buffer holds the order for the last view (gl_renderer_meshes.cpp).
    GpuMesh m_transparent;
    core::TriangleDepthOrder m_transparentOrder;
    core::BoundingSphere m_meshBounds;
    std::vector<BoxOverlay> m_boxes;
    std::optional<BoxHandlesOverlay> m_selected;
    gl::BufferTexture m_segmentsTex; // 3 RGBA32F texels per edge
    std::size_t m_segmentCount = 0;
    gl::BufferTexture m_handleSpheresTex, m_handleRowsTex;

    gl::VertexArray m_emptyVao;
    gl::VertexArray m_overlayVao;
    gl::Buffer m_overlayVbo;
    std::map<int, std::unique_ptr<FontTexture>> m_fonts; // by pixel height
    bool m_fontMissingReported = false;

    gl::RenderTexture m_scene;        // supersampled colour + depth
    gl::RenderTexture m_occlusion;    // supersampled occlusion (red), before blurring
    gl::RenderTexture m_contextLayer; // hidden spheres as points (scene depth, not written)
    gl::RenderTexture m_composite;    // supersampled colour after darkening (supersample > 1)
    gl::RenderTexture m_output;       // final size, what colorTexture() shows
    RenderTarget m_lastTarget{0, 0};

    // Passes (gl_renderer.cpp)
    void drawSpheres(const FrameSetup& f);
    void drawSphereRows(const gl::BufferTexture& rows, std::size_t count);
    void useSphereProgram(const FrameSetup& f);
    void drawContextPoints(const FrameSetup& f);
    // Meshes (gl_renderer_meshes.cpp)
    static GpuMesh uploadMesh(std::span<const float> vertices,
                              std::span<const std::uint32_t> indices, GLenum indexUsage);
    void useMeshProgram(const FrameSetup& f);
    void drawOpaqueMeshes(const FrameSetup& f);
    void drawTransparentMeshes(const FrameSetup& f);
    void drawBoxEdges(const FrameSetup& f, float widthPx, float alpha, bool depthTest);
    // Passes (gl_renderer_overlay.cpp)
    void composite(const FrameSetup& f, const RenderTarget& target);
    void drawHandles(const FrameSetup& f);
    void drawLegend(const RenderTarget& target);
    FontTexture* font(int pixelHeight);
    void uploadSegments();
    void bindColorMap(GLuint program, GLuint unit);
};

} // namespace faultline::ui
