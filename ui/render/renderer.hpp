// The renderer's contract with viewports, `faultline render` and tests: spheres, colour map,
// visibility, meshes, boxes and a camera in; an image out. Two back ends, chosen at start:
// OpenGL (needs a current 4.1+ context) and Mock (records what would be drawn; no display).
#pragma once

#include "core/color/colormap.hpp"
#include "core/view/box_handles.hpp"
#include "core/view/camera.hpp"
#include "ui/render/legend_layout.hpp"
#include "ui/render/png_image.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace faultline::ui {

enum class RendererBackend { OpenGL, Mock };

// One frame's spheres as columns (see core::Frame). Copied on upload.
struct SphereColumns {
    std::span<const float> x, y, z, radius;
    // What the radii are drawn (and culled and picked) at: core::radiusDrawScale, below 1 only
    // for radii far larger than the centres' spacing.
    float radiusScale = 1.0f;
};

// A triangle mesh (e.g. a fault surface) with per-vertex colour and one opacity.
struct MeshData {
    std::vector<float> positions;       // x y z per vertex, world
    std::vector<float> normals;         // x y z per vertex (unit); may be empty: flat shading
    std::vector<float> colors;          // r g b per vertex in 0..1 (sRGB); may be empty: grey
    std::vector<std::uint32_t> indices; // three per triangle
    float opacity = 1.0f;
};

// A cutting box drawn as a wireframe.
struct BoxOverlay {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
    glm::vec3 color{0.15f, 0.15f, 0.15f};
};

// The selected box shows one draggable handle per face (see core/view/box_handles.hpp).
struct BoxHandlesOverlay {
    std::size_t box = 0;                     // index into the boxes given with it
    double handleRadius = 0.0;               // world units; 0: core::defaultHandleRadius
    std::optional<core::BoxFace> activeFace; // drawn highlighted (hovered or dragged)
};

// Software GL (llvmpipe) shades every fragment of a depth-writing impostor, so hidden spheres
// cost as much as visible ones; culling them first pays there and costs a read-back elsewhere.
enum class OcclusionCulling { Off, On, Auto /* on for software renderers */ };

struct RenderStyle {
    glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f}; // sRGB
    glm::vec3 sphereColor{0.78f, 0.74f, 0.68f};   // when no values are set
    float specular = 0.35f;
    bool ambientOcclusion = true; // screen-space contact darkening
    float aoStrength = 0.9f;
    bool contextPoints = false;                         // hidden spheres as faint small points
    glm::vec4 contextColor{0.45f, 0.48f, 0.55f, 0.22f}; // alpha: opacity of the ghost layer
    float contextPointSize = 2.0f;                      // pixels at the output size
    float lineWidth = 2.0f;                             // box edges, pixels at the output size
    bool showLegend = true;                             // drawn only when sphere values are set
    std::string legendTitle;                            // the variable's name
    // Not empty: the legend names these colours (faults) instead of showing a colour bar.
    std::vector<LegendEntry> categories;
    bool integerValues = false; // legend ticks at whole numbers (e.g. broken bonds)
    float legendScale = 1.0f;   // on top of the automatic size (output height / 720)
    std::string caption;        // a label in the top-left corner (a movie frame's timestep)
    OcclusionCulling culling = OcclusionCulling::Auto;
};

struct RenderTarget {
    int width = 1280;
    int height = 720;
    int supersample = 1;      // 1..4: render s x s samples per pixel, then average (offscreen AA)
    bool transparent = false; // background alpha 0 (the PNG keeps the alpha)
};

struct RenderStats {
    // Uploads since creation: how often each kind of data went to the GPU.
    std::uint64_t positionUploads = 0;
    std::uint64_t valueUploads = 0;
    std::uint64_t visibilityUploads = 0;
    std::uint64_t colorMapUploads = 0;
    std::uint64_t meshUploads = 0;
    std::uint64_t meshSorts = 0; // transparent triangles re-sorted (the view or meshes changed)
    // The last render.
    std::size_t spheres = 0;        // rows set
    std::size_t visibleSpheres = 0; // rows the mask shows
    std::size_t drawnSpheres = 0;   // impostors drawn (visible minus culled)
    std::size_t occluderPasses = 0;
    std::size_t frustumCulled = 0;
    std::size_t occlusionCulled = 0;
    std::size_t contextPoints = 0;
    std::size_t meshTriangles = 0;
    std::size_t boxes = 0;
    std::size_t handles = 0;
    std::size_t legendTicks = 0;
};

class Renderer {
  public:
    virtual ~Renderer() = default;
    virtual RendererBackend backend() const = 0;

    // A new frame's spheres: uploads centres and radii (once per frame), resets the values (one
    // colour) and the visibility (all visible).
    virtual void setSpheres(const SphereColumns& spheres) = 0;
    // The colour variable, one value per row (NaN: grey); empty: every sphere in one colour.
    virtual void setSphereValues(std::span<const float> values) = 0;
    // 1 = visible, one byte per row; empty: all visible. Only the compact list of visible rows is
    // uploaded, never the positions.
    virtual void setVisibleMask(std::span<const std::uint8_t> mask) = 0;
    // Map and range change a small texture and two uniforms; nothing per sphere is re-sent.
    virtual void setColorMap(const core::ColorMapSpec& map) = 0;
    virtual void setColorRange(core::ValueRange range) = 0;
    virtual void setMeshes(std::span<const MeshData> meshes) = 0;
    virtual void setBoxes(std::span<const BoxOverlay> boxes,
                          std::optional<BoxHandlesOverlay> selected) = 0;
    virtual void setStyle(const RenderStyle& style) = 0;

    // Draws the scene into the renderer's own target (see colorTexture / readImage).
    virtual void render(const core::Camera& camera, const RenderTarget& target) = 0;
    // The last render, top row first, straight (not premultiplied) alpha.
    virtual RgbaImage readImage() = 0;
    // The OpenGL texture holding the last render (for ImGui::Image); 0 for the mock.
    virtual unsigned int colorTexture() const = 0;

    virtual const RenderStats& stats() const = 0;
    // Everything set so far (all spheres, meshes, boxes): for clip planes and "fit all".
    virtual core::BoundingSphere sceneBounds() const = 0;
};

// OpenGL throws std::runtime_error (with the reason) when no usable context is current.
std::unique_ptr<Renderer> createRenderer(RendererBackend backend);

// Rows whose mask byte is non-zero (all rows when the mask is empty), and the others.
void compactRows(std::size_t count, std::span<const std::uint8_t> mask,
                 std::vector<std::uint32_t>& visible, std::vector<std::uint32_t>* hidden);

} // namespace faultline::ui
