// GuiApp: the workbench in a GLFW window with an OpenGL 4.5 core context: events (including
// files dropped on the window), content scale for high-DPI screens, the frame loop, and window
// screenshots. Tests drive it frame by frame and may feed input after the devices are read.
#pragma once

#include "ui/workbench/workbench.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

struct GLFWwindow;
struct ImGuiIO;

namespace faultline::ui {

struct GuiOptions {
    int width = 1600, height = 1000; // window size in screen coordinates (before content scale)
    bool maximize = true;
    std::string title = "Faultline";
    WorkbenchOptions workbench;
};

class GuiApp {
  public:
    // Opens the window and the ImGui context. Throws std::runtime_error with the reason when no
    // window or OpenGL 4.x context can be had.
    GuiApp(core::Session& session, GuiOptions options);
    ~GuiApp();
    GuiApp(const GuiApp&) = delete;
    GuiApp& operator=(const GuiApp&) = delete;

    Workbench& workbench() { return *m_workbench; }
    GLFWwindow* window() const { return m_window; }

    // One frame: events, UI, views, draw, swap. False once the window should close. `wait`:
    // sleep until an event arrives when nothing is animating (idle CPU), else poll.
    bool step(bool wait = false);
    // Until the window is closed; returns the exit code.
    int run();

    // Called every frame after the devices are read, before the UI is built (tests).
    void setInputHook(std::function<void(ImGuiIO&)> hook) { m_inputHook = std::move(hook); }
    // The last drawn frame as a PNG (the back buffer before the swap). False on failure.
    bool saveScreenshot(const std::string& path);
    // Files dropped on the window (also reached by synthetic drops in tests).
    void dropFiles(const std::vector<std::string>& paths);

  private:
    static void onDrop(GLFWwindow* window, int count, const char** paths);
    static void onContentScale(GLFWwindow* window, float x, float y);
    void setScale(float scale);
    bool animating() const;

    GLFWwindow* m_window = nullptr;
    std::string m_title; // the window title last set
    // Idle frames whose picture would not change are not drawn or presented (the window keeps
    // the last one): the draw lists' hash and the views' draw count of the last presented frame.
    std::uint64_t m_presentedHash = 0;
    std::size_t m_presentedDraws = ~std::size_t{0};
    int m_presentedWidth = 0, m_presentedHeight = 0;
    bool m_exposed = true; // the window system asked for a redraw
    std::size_t m_presentedFrames = 0, m_skippedFrames = 0;

  public:
    // Frames drawn and presented, and idle frames skipped because nothing changed (tests).
    std::size_t presentedFrames() const { return m_presentedFrames; }
    std::size_t skippedFrames() const { return m_skippedFrames; }

  private:
    static void onRefresh(GLFWwindow* window);
    std::unique_ptr<Workbench> m_workbench;
    std::unique_ptr<ViewRenderer> m_renderer; // null when this OpenGL cannot draw spheres
    std::function<void(ImGuiIO&)> m_inputHook;
    float m_scale = 1.0f;
    float m_pendingScale = 0.0f;
    bool m_imguiReady = false;
};

} // namespace faultline::ui
