// Rendering without a visible window, for `faultline render`, figures and image tests: a hidden
// GLFW window or, with no display at all, EGL provides the OpenGL context; a scene description
// becomes an image or a PNG.
#pragma once

#include "core/model/frame.hpp"
#include "ui/render/renderer.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace faultline::ui {

// Everything one picture shows. The frame is borrowed: it must outlive the call.
struct SceneDescription {
    const core::Frame* frame = nullptr; // null: meshes and boxes only
    std::vector<std::uint8_t> visible;  // a byte per row, 1 = visible; empty: all
    std::string colorVariable;          // empty: every sphere in style.sphereColor
    // Values instead of colorVariable's column (difference colouring; colorVariable titles the
    // legend). One per sphere of the frame.
    const core::AttributeColumn* colorColumn = nullptr;
    core::ColorMapSpec colorMap;
    std::optional<core::ValueRange> colorRange; // empty: the variable's min..max in this frame
    std::vector<MeshData> meshes;
    std::vector<BoxOverlay> boxes;
    std::optional<BoxHandlesOverlay> selectedBox;
    std::optional<core::Camera> camera; // empty: fittedCamera(..., Iso)
    RenderStyle style;                  // an empty legendTitle becomes colorVariable
};

struct RenderSettings {
    int width = 1920;
    int height = 1080;
    bool transparent = false;
    int supersample = 0; // 0: 2 x 2 samples per pixel up to 4096 wide, else 1; or 1..4
};

// The preset's direction, fitted (core::fitBox) to the visible spheres (all of them when none is
// visible), meshes and boxes of a width x height image, leaving room for the legend.
core::Camera fittedCamera(const SceneDescription& scene, int width, int height,
                          core::ViewPreset preset = core::ViewPreset::Iso);
// Whether the scene's image gets a colour-bar legend.
bool showsLegend(const SceneDescription& scene);
// Pixels from the right edge that the scene's legend takes in a width x height image.
double legendPixels(const SceneDescription& scene, int width, int height);

// Loads the scene into a renderer (any back end): spheres, values, range, map, mask, meshes,
// boxes, style. Throws std::invalid_argument naming the variable when the frame lacks it.
void loadScene(Renderer& renderer, const SceneDescription& scene);

// Renders with the current OpenGL context, or the shared offscreen one when none is current.
// Throws std::runtime_error when no OpenGL context can be had (no display), with the reason.
RgbaImage renderSceneToImage(const SceneDescription& scene, const RenderSettings& settings);
void renderSceneToPng(const SceneDescription& scene, const RenderSettings& settings,
                      const std::string& path);

class OffscreenContext {
  public:
    // An OpenGL 4.1+ core context made current on this thread, without a visible window: a
    // hidden GLFW window when a display is set, else EGL without any X server (Mesa's
    // surfaceless platform, or an EGL device: a GPU node's driver). FAULTLINE_OFFSCREEN=egl or
    // =glfw forces one. Null and the reason in `why` when none can be made.
    static std::unique_ptr<OffscreenContext> create(std::string& why);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;
    void makeCurrent();
    // Whether this context is the current one on this thread (false once GLFW was terminated
    // under a GLFW context, as a closed workbench window does).
    bool isCurrent() const;
    // "glfw" or "egl (surfaceless)" / "egl (device N)": what made the context.
    const std::string& kind() const { return m_kind; }
    struct Egl; // EGL display and context (offscreen.cpp)

  private:
    OffscreenContext() = default;
    GLFWwindow* m_window = nullptr;
    std::unique_ptr<Egl> m_egl;
    std::string m_kind;
};

// Whether this thread has a current OpenGL context (a window's, or an offscreen one).
bool hasCurrentGlContext();

// One context for the whole process, made on first use (kept until exit); null and `why` when
// none can be made.
OffscreenContext* sharedOffscreenContext(std::string& why);

} // namespace faultline::ui
