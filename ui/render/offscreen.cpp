#include "ui/render/offscreen.hpp"

#include "ui/render/legend_layout.hpp"

#include <GLFW/glfw3.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace faultline::ui {

namespace {

std::string g_lastGlfwError;
void onGlfwError(int, const char* description) { g_lastGlfwError = description ? description : ""; }

std::vector<float> columnValues(const core::AttributeColumn& column) {
    if (!column.isInteger())
        return column.floats;
    return {column.ints.begin(), column.ints.end()};
}

} // namespace

std::unique_ptr<OffscreenContext> OffscreenContext::create(std::string& why) {
    glfwSetErrorCallback(onGlfwError);
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        why = "no display (DISPLAY is not set; run under xvfb-run for headless rendering)";
        return nullptr;
    }
    if (!glfwInit()) {
        why = "cannot open the display: " + g_lastGlfwError;
        return nullptr;
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow* window = glfwCreateWindow(16, 16, "faultline offscreen", nullptr, nullptr);
    if (!window) {
        why = "cannot create an OpenGL 4.1 core context: " + g_lastGlfwError;
        return nullptr;
    }
    glfwMakeContextCurrent(window);
    return std::unique_ptr<OffscreenContext>(new OffscreenContext(window));
}

OffscreenContext::~OffscreenContext() {
    if (glfwGetCurrentContext() == m_window)
        glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(m_window);
}

void OffscreenContext::makeCurrent() { glfwMakeContextCurrent(m_window); }

OffscreenContext* sharedOffscreenContext(std::string& why) {
    static std::mutex mutex;
    // Deliberately leaked: GLFW must not be torn down during static destruction.
    static OffscreenContext* context = nullptr;
    static std::string failure;
    static bool tried = false;
    std::lock_guard lock(mutex);
    if (!tried) {
        tried = true;
        context = OffscreenContext::create(failure).release();
    }
    if (!context) {
        why = failure;
        return nullptr;
    }
    context->makeCurrent();
    return context;
}

bool showsLegend(const SceneDescription& scene) {
    return scene.style.showLegend && scene.frame && !scene.colorVariable.empty();
}

core::Camera fittedCamera(const SceneDescription& scene, int width, int height,
                          core::ViewPreset preset) {
    core::Aabb box;
    if (const core::Frame* f = scene.frame; f && f->size() > 0) {
        box = core::boundsOf(f->x, f->y, f->z, f->radius, scene.visible);
        if (!box.valid) // nothing visible: frame them all
            box = core::boundsOf(f->x, f->y, f->z, f->radius);
    }
    for (const MeshData& m : scene.meshes) {
        for (std::size_t v = 0; v + 2 < m.positions.size(); v += 3)
            box.extend(glm::dvec3(m.positions[v], m.positions[v + 1], m.positions[v + 2]));
    }
    for (const BoxOverlay& b : scene.boxes) {
        box.extend(b.lo);
        box.extend(b.hi);
    }
    if (!box.valid)
        box.extend(glm::dvec3(-1.0)), box.extend(glm::dvec3(1.0));
    core::Camera camera;
    core::applyPreset(camera, preset);
    width = std::max(width, 1);
    height = std::max(height, 1);
    // Leave the legend its strip on the right: fit the rest, then shift the scene left.
    double legend = 0.0;
    if (showsLegend(scene))
        legend = std::min(0.4 * width, 115.0 * legendScale(width, height, scene.style.legendScale));
    core::fitBox(camera, box, (width - legend) / double(height), 1.08);
    core::pan(camera, {-legend / width, 0.0}, double(width) / height);
    return camera;
}

void loadScene(Renderer& renderer, const SceneDescription& scene) {
    const core::Frame* f = scene.frame;
    RenderStyle style = scene.style;
    if (style.legendTitle.empty())
        style.legendTitle = scene.colorVariable;
    renderer.setStyle(style);
    if (f) {
        renderer.setSpheres({f->x, f->y, f->z, f->radius});
        if (!scene.colorVariable.empty()) {
            const core::AttributeColumn* column =
                scene.colorColumn ? scene.colorColumn : f->attribute(scene.colorVariable);
            if (column && column->size() != f->size())
                throw std::invalid_argument("the colour column has " + std::to_string(column->size()) +
                                            " values for " + std::to_string(f->size()) + " spheres");
            if (!column) {
                std::string names;
                for (const std::string& n : f->attributeNames())
                    names += (names.empty() ? "" : ", ") + n;
                throw std::invalid_argument("no variable '" + scene.colorVariable +
                                            "' in this frame (it has: " + names + ")");
            }
            style.integerValues = column->isInteger();
            renderer.setStyle(style);
            const std::vector<float> values = columnValues(*column);
            renderer.setSphereValues(values);
            renderer.setColorRange(scene.colorRange ? *scene.colorRange
                                                    : core::ValueRange{column->min, column->max});
        }
        if (!scene.visible.empty()) {
            if (scene.visible.size() != f->size())
                throw std::invalid_argument("the visibility mask has " +
                                            std::to_string(scene.visible.size()) + " entries for " +
                                            std::to_string(f->size()) + " spheres");
            renderer.setVisibleMask(scene.visible);
        }
    }
    renderer.setColorMap(scene.colorMap);
    renderer.setMeshes(scene.meshes);
    renderer.setBoxes(scene.boxes, scene.selectedBox);
}

RgbaImage renderSceneToImage(const SceneDescription& scene, const RenderSettings& settings) {
    if (settings.width <= 0 || settings.height <= 0)
        throw std::invalid_argument("image size must be positive");
    if (!glfwGetCurrentContext()) {
        std::string why;
        if (!sharedOffscreenContext(why))
            throw std::runtime_error("cannot render: " + why);
    }
    std::unique_ptr<Renderer> renderer = createRenderer(RendererBackend::OpenGL);
    loadScene(*renderer, scene);
    const core::Camera camera =
        scene.camera ? *scene.camera : fittedCamera(scene, settings.width, settings.height);
    RenderTarget target{settings.width, settings.height, settings.supersample,
                        settings.transparent};
    if (target.supersample <= 0)
        target.supersample = std::max(settings.width, settings.height) <= 4096 ? 2 : 1;
    renderer->render(camera, target);
    return renderer->readImage();
}

void renderSceneToPng(const SceneDescription& scene, const RenderSettings& settings,
                      const std::string& path) {
    writePng(renderSceneToImage(scene, settings), path);
}

} // namespace faultline::ui
