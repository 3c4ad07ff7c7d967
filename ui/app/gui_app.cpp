#include "ui/app/gui_app.hpp"

#include "ui/app/theme.hpp"
#include "ui/viewport/gl_view_renderer.hpp"

// epoxy must come before any GL header (GLFW includes GL/gl.h).
#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace faultline::ui {

GuiApp::GuiApp(core::Session& session, GuiOptions options) {
    if (!glfwInit()) {
        const char* why = nullptr;
        glfwGetError(&why);
        throw std::runtime_error(std::string("cannot open a window: ") +
                                 (why ? why : "GLFW failed to start"));
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    glfwWindowHint(GLFW_MAXIMIZED, options.maximize ? GLFW_TRUE : GLFW_FALSE);
    // Within the screen's work area: where no window manager maximizes the window (a bare X
    // server, some tiling setups), 1600 x 1000 on a 1600 x 900 screen hid the status line.
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor(); monitor && options.maximize) {
        int x = 0, y = 0, w = 0, h = 0;
        glfwGetMonitorWorkarea(monitor, &x, &y, &w, &h);
        if (w > 0 && h > 0) {
            options.width = std::min(options.width, w);
            options.height = std::min(options.height, h);
        }
    }
    m_window =
        glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!m_window) {
        // Some drivers offer 4.1 at most (macOS-like stacks); the workbench needs no more.
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
        m_window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr,
                                    nullptr);
    }
    if (!m_window) {
        const char* why = nullptr;
        glfwGetError(&why);
        glfwTerminate();
        throw std::runtime_error(std::string("cannot create an OpenGL 4 window: ") +
                                 (why ? why : "unknown reason"));
    }
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(m_window, this);
    glfwSetDropCallback(m_window, &GuiApp::onDrop);
    glfwSetWindowContentScaleCallback(m_window, &GuiApp::onContentScale);
    glfwSetWindowRefreshCallback(m_window, &GuiApp::onRefresh);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // the layout lives in the session
    io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;
    ImGui_ImplGlfw_InitForOpenGL(m_window, true);
    ImGui_ImplOpenGL3_Init("#version 410 core");
    m_imguiReady = true;
    float sx = 1, sy = 1;
    glfwGetWindowContentScale(m_window, &sx, &sy);
    // FAULTLINE_UI_SCALE overrides the monitor's content scale (X11 without Xft.dpi, tests).
    if (const char* env = std::getenv("FAULTLINE_UI_SCALE");
        env && std::atof(env) >= 0.5 && std::atof(env) <= 4)
        sx = static_cast<float>(std::atof(env));
    m_workbench = std::make_unique<Workbench>(session, std::move(options.workbench));
    setScale(std::max(1.0f, std::round(sx * 4) / 4));
    try {
        m_renderer = std::make_unique<GlViewRenderer>();
        m_workbench->setRenderer(m_renderer.get());
    } catch (const std::exception& e) {
        m_workbench->error(std::string("The 3-D views are off: ") + e.what());
    }
    auto wake = [] { glfwPostEmptyEvent(); };
    m_workbench->jobs().setWakeUp(wake);
    m_workbench->frames().setWakeUp(wake);
}

GuiApp::~GuiApp() {
    if (m_workbench)
        m_workbench->setRenderer(nullptr);
    m_workbench.reset();
    m_renderer.reset(); // GL objects go while the context is current
    if (m_imguiReady) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (m_window)
        glfwDestroyWindow(m_window);
    glfwTerminate();
}

void GuiApp::setScale(float scale) {
    m_scale = scale;
    applyTheme(scale);
    loadFonts(scale);
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
    m_workbench->setScale(scale);
}

void GuiApp::onDrop(GLFWwindow* window, int count, const char** paths) {
    auto* self = static_cast<GuiApp*>(glfwGetWindowUserPointer(window));
    std::vector<std::string> list(paths, paths + count);
    self->dropFiles(list);
}

void GuiApp::onContentScale(GLFWwindow* window, float x, float) {
    auto* self = static_cast<GuiApp*>(glfwGetWindowUserPointer(window));
    self->m_pendingScale = std::max(1.0f, std::round(x * 4) / 4);
}

void GuiApp::onRefresh(GLFWwindow* window) {
    static_cast<GuiApp*>(glfwGetWindowUserPointer(window))->m_exposed = true;
}

namespace {

// FNV-1a over the draw lists: vertices, indices and commands (clip rectangles, textures).
std::uint64_t hashDrawData(const ImDrawData* data) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* p, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        // Eight bytes at a time: a megabyte of vertices costs well under a millisecond.
        std::size_t i = 0;
        for (; i + 8 <= n; i += 8) {
            std::uint64_t v;
            std::memcpy(&v, b + i, 8);
            h = (h ^ v) * 1099511628211ull;
        }
        for (; i < n; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    };
    if (!data)
        return h;
    mix(&data->DisplaySize, sizeof data->DisplaySize);
    for (int l = 0; l < data->CmdListsCount; ++l) {
        const ImDrawList* list = data->CmdLists[l];
        mix(list->VtxBuffer.Data,
            static_cast<std::size_t>(list->VtxBuffer.Size) * sizeof(ImDrawVert));
        mix(list->IdxBuffer.Data,
            static_cast<std::size_t>(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
        for (const ImDrawCmd& c : list->CmdBuffer) {
            mix(&c.ClipRect, sizeof c.ClipRect);
            mix(&c.TextureId, sizeof c.TextureId);
            mix(&c.ElemCount, sizeof c.ElemCount);
            mix(&c.IdxOffset, sizeof c.IdxOffset);
            mix(&c.VtxOffset, sizeof c.VtxOffset);
        }
    }
    return h;
}

} // namespace

void GuiApp::dropFiles(const std::vector<std::string>& paths) {
    if (paths.empty())
        return;
    // Several files dropped together are one run's frames; one file may also be a session.
    if (paths.size() == 1)
        m_workbench->opener().openPath(paths.front());
    else
        m_workbench->opener().openData(paths);
}

bool GuiApp::animating() const {
    return m_workbench->playback().playing || m_workbench->jobs().busy() ||
           m_workbench->frames().loading().has_value();
}

bool GuiApp::step(bool wait) {
    if (!wait || m_workbench->playback().playing)
        glfwPollEvents(); // the swap's vsync paces playback
    else if (animating())
        glfwWaitEventsTimeout(0.05); // progress bars at 20 frames per second; input wakes at once
    else
        glfwWaitEventsTimeout(0.25); // idle: autosave and message timeouts still run
    if (m_pendingScale > 0 && m_pendingScale != m_scale) {
        setScale(m_pendingScale);
        m_pendingScale = 0;
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (m_inputHook)
        m_inputHook(ImGui::GetIO());
    ImGui::NewFrame();
    m_workbench->frame(glfwGetTime());
    m_workbench->renderViews();
    ImGui::Render();
    int w = 0, h = 0;
    glfwGetFramebufferSize(m_window, &w, &h);
    // An idle frame that would look exactly like the one on screen (same draw lists, no view
    // drawn again, same size) is neither drawn nor presented: the window keeps the last picture.
    // That is most of an idle workbench's cost with a software renderer.
    const std::uint64_t drawHash = hashDrawData(ImGui::GetDrawData());
    const auto* views = dynamic_cast<const GlViewRenderer*>(m_renderer.get());
    const std::size_t draws = views ? views->drawCount() : 0;
    const bool screenshot = m_workbench->hasScreenshotRequest();
    const bool same = wait && !m_exposed && !screenshot && drawHash == m_presentedHash &&
                      draws == m_presentedDraws && w == m_presentedWidth && h == m_presentedHeight;
    if (same) {
        ++m_skippedFrames;
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, w, h);
        glClearColor(0.82f, 0.84f, 0.87f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (auto path = m_workbench->takeScreenshotRequest()) {
            if (saveScreenshot(*path))
                m_workbench->info("Saved a screenshot to " + *path);
            else
                m_workbench->error("Cannot write the screenshot " + *path);
        }
        glfwSwapBuffers(m_window);
        m_presentedHash = drawHash, m_presentedDraws = draws;
        m_presentedWidth = w, m_presentedHeight = h;
        m_exposed = false;
        ++m_presentedFrames;
    }
    // The window's close button asks like Quit does when work is unsaved.
    if (glfwWindowShouldClose(m_window) && !m_workbench->quitRequested()) {
        glfwSetWindowShouldClose(m_window, GLFW_FALSE);
        m_workbench->requestQuit();
    }
    if (m_workbench->quitRequested())
        glfwSetWindowShouldClose(m_window, GLFW_TRUE);
    const std::string title = m_workbench->windowTitle();
    if (title != m_title) {
        glfwSetWindowTitle(m_window, title.c_str());
        m_title = title;
    }
    return !glfwWindowShouldClose(m_window);
}

int GuiApp::run() {
    while (step(true)) {
    }
    return 0;
}

bool GuiApp::saveScreenshot(const std::string& path) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(m_window, &w, &h);
    if (w <= 0 || h <= 0)
        return false;
    std::vector<unsigned char> pixels(static_cast<std::size_t>(w) * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    std::vector<unsigned char> flipped(pixels.size());
    const std::size_t row = static_cast<std::size_t>(w) * 4;
    for (int y = 0; y < h; ++y)
        std::copy_n(pixels.data() + static_cast<std::size_t>(h - 1 - y) * row, row,
                    flipped.data() + static_cast<std::size_t>(y) * row);
    for (std::size_t k = 3; k < flipped.size(); k += 4)
        flipped[k] = 255;
    return stbi_write_png(path.c_str(), w, h, 4, flipped.data(), static_cast<int>(row)) != 0;
}

} // namespace faultline::ui
