#include "ui/render/offscreen.hpp"

#include "core/model/packing.hpp"
#include "core/selection/column_view.hpp"

#include "ui/render/legend_layout.hpp"

#include <epoxy/egl.h> // before GLFW, whose header would bring GL/gl.h
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <span>
#include <stdexcept>
#include <vector>

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

struct OffscreenContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

namespace {

std::string eglErrorText() {
    char text[32];
    std::snprintf(text, sizeof text, "EGL error 0x%04x", static_cast<unsigned>(eglGetError()));
    return text;
}

// An OpenGL 4.1 core context on `display` (initialised here), current without a surface.
EGLContext eglCoreContext(EGLDisplay display, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed (" + eglErrorText() + ")";
        return EGL_NO_CONTEXT;
    }
    if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
        why = "the EGL display cannot make a context current without a surface";
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "EGL has no desktop OpenGL (" + eglErrorText() + ")";
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count < 1) {
        // Some drivers list no surface-less configs; any OpenGL one serves an FBO.
        const EGLint anyOpenGl[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        if (!eglChooseConfig(display, anyOpenGl, &config, 1, &count) || count < 1)
            config = nullptr;
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        1,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, config ? config : EGL_NO_CONFIG_KHR,
                                          EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
        why = "cannot create an OpenGL 4.1 core context through EGL (" + eglErrorText() + ")";
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        why = "cannot make the EGL context current (" + eglErrorText() + ")";
        eglDestroyContext(display, context);
        eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    return context;
}

// Displays to try, in order: Mesa's surfaceless platform (any Mesa driver, llvmpipe included),
// then each EGL device (NVIDIA's and other vendors' drivers on compute nodes).
std::unique_ptr<OffscreenContext::Egl> createEgl(std::string& kind, std::string& why) {
    std::vector<std::pair<std::string, EGLDisplay>> displays;
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
        displays.emplace_back(
            "egl (surfaceless)",
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") &&
        epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count))
            for (EGLint k = 0; k < count; ++k)
                displays.emplace_back(
                    "egl (device " + std::to_string(k) + ")",
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[k], nullptr));
    }
    if (displays.empty()) {
        why = "no display (DISPLAY is not set) and EGL offers neither a surfaceless platform nor "
              "devices";
        return nullptr;
    }
    std::string reasons;
    for (const auto& [name, display] : displays) {
        if (display == EGL_NO_DISPLAY)
            continue;
        std::string reason;
        EGLContext context = eglCoreContext(display, reason);
        if (context != EGL_NO_CONTEXT) {
            kind = name;
            auto egl = std::make_unique<OffscreenContext::Egl>();
            egl->display = display;
            egl->context = context;
            return egl;
        }
        reasons += (reasons.empty() ? "" : "; ") + name + ": " + reason;
    }
    why = "no display (DISPLAY is not set) and no EGL context: " +
          (reasons.empty() ? std::string("no EGL display could be opened") : reasons);
    return nullptr;
}

} // namespace

std::unique_ptr<OffscreenContext> OffscreenContext::create(std::string& why) {
    glfwSetErrorCallback(onGlfwError);
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    const char* force = std::getenv("FAULTLINE_OFFSCREEN");
    const std::string forced = force ? force : "";
    const bool haveDisplay = (display && *display) || (wayland && *wayland);
    std::unique_ptr<OffscreenContext> result(new OffscreenContext());
    if (forced == "egl" || (!haveDisplay && forced != "glfw")) {
        result->m_egl = createEgl(result->m_kind, why);
        if (!result->m_egl)
            return nullptr;
        return result;
    }
    if (!haveDisplay) {
        why = "no display (DISPLAY is not set) and FAULTLINE_OFFSCREEN=glfw";
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
    result->m_window = window;
    result->m_kind = "glfw";
    return result;
}

OffscreenContext::~OffscreenContext() {
    if (m_egl) {
        if (eglGetCurrentContext() == m_egl->context)
            eglMakeCurrent(m_egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(m_egl->display, m_egl->context);
        eglTerminate(m_egl->display);
        return;
    }
    if (glfwGetCurrentContext() == m_window)
        glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(m_window);
}

bool OffscreenContext::isCurrent() const {
    if (m_egl)
        return eglGetCurrentContext() == m_egl->context;
    return glfwGetCurrentContext() == m_window; // null (and an error) once GLFW was terminated
}

void OffscreenContext::makeCurrent() {
    if (m_egl)
        eglMakeCurrent(m_egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_egl->context);
    else
        glfwMakeContextCurrent(m_window);
}

namespace {
thread_local bool t_eglCurrent = false; // an OffscreenContext's EGL context is current here
}

bool hasCurrentGlContext() {
    // Without an initialised GLFW this returns null (and reports an error to the callback).
    return t_eglCurrent || glfwGetCurrentContext() != nullptr;
}

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
    if (!context->isCurrent()) {
        // GLFW was terminated since (a workbench window closed in this process, as in the
        // tests), taking the hidden window with it: make another. The old one is left as it
        // is (destroying its window now would touch a GLFW that no longer knows it).
        context = OffscreenContext::create(failure).release();
        if (!context) {
            why = failure;
            return nullptr;
        }
    }
    t_eglCurrent = context->kind() != "glfw";
    return context;
}

bool showsLegend(const SceneDescription& scene) {
    return scene.style.showLegend && scene.frame && !scene.colorVariable.empty();
}

double legendPixels(const SceneDescription& scene, int width, int height) {
    core::ValueRange range{0, 1};
    if (scene.colorRange)
        range = *scene.colorRange;
    else if (scene.frame)
        if (const core::AttributeColumn* c =
                scene.colorColumn ? scene.colorColumn : scene.frame->attribute(scene.colorVariable))
            range = {c->min, c->max};
    const std::string& title =
        scene.style.legendTitle.empty() ? scene.colorVariable : scene.style.legendTitle;
    return legendStripPixels(title, range, scene.style.integerValues, scene.style.categories, width,
                             height, scene.style.legendScale);
}

core::Camera fittedCamera(const SceneDescription& scene, int width, int height,
                          core::ViewPreset preset) {
    core::Aabb box;
    if (const core::Frame* f = scene.frame; f && f->size() > 0) {
        // The radii as drawn (loadScene): scaled down where far larger than the spacing.
        std::vector<float> scaled;
        std::span<const float> radii = f->radius;
        if (const double k = core::radiusDrawScale(*f); k != 1.0) {
            scaled.assign(f->radius.begin(), f->radius.end());
            for (float& r : scaled)
                r = float(r * k);
            radii = scaled;
        }
        box = core::boundsOf(f->x, f->y, f->z, radii, scene.visible);
        if (!box.valid) // nothing visible: frame them all
            box = core::boundsOf(f->x, f->y, f->z, radii);
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
        legend = std::min(0.45 * width, legendPixels(scene, width, height));
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
        renderer.setSpheres({f->x, f->y, f->z, f->radius, float(core::radiusDrawScale(*f))});
        if (!scene.colorVariable.empty()) {
            const core::AttributeColumn* column =
                scene.colorColumn ? scene.colorColumn : f->attribute(scene.colorVariable);
            if (column && column->size() != f->size())
                throw std::invalid_argument("the colour column has " +
                                            std::to_string(column->size()) + " values for " +
                                            std::to_string(f->size()) + " spheres");
            // Positions are variables too (issue 41): colour by height to see layers offset.
            const auto position = column ? std::nullopt : core::findColumn(*f, scene.colorVariable);
            if (position) {
                renderer.setSphereValues({position->floats, position->size});
                const auto r = core::variableRange(*f, scene.colorVariable);
                renderer.setColorRange(scene.colorRange ? *scene.colorRange
                                       : r              ? core::ValueRange{r->low, r->high}
                                                        : core::ValueRange{0, 1});
            } else if (!column) {
                throw std::invalid_argument(core::missingVariableNote(*f, scene.colorVariable));
            } else {
                style.integerValues = column->isInteger();
                renderer.setStyle(style);
                const std::vector<float> values = columnValues(*column);
                renderer.setSphereValues(values);
                renderer.setColorRange(scene.colorRange
                                           ? *scene.colorRange
                                           : core::ValueRange{column->min, column->max});
            }
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
    if (!hasCurrentGlContext()) {
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
