// HeadlessUi: a Dear ImGui context with no display (display size set, font atlas built, no
// GL back end) that runs the workbench frame by frame and feeds it mouse and keys, finding
// widgets by the names panels mark (ItemRegistry). Shared by the panel tests.
#pragma once

#include "../core/lattice_dump.hpp"
#include "core/session/session.hpp"
#include "ui/workbench/workbench.hpp"

#include <GLFW/glfw3.h> // key codes only
#include <gtest/gtest.h>
#include <imgui.h>

#include <string>
#include <vector>

namespace faultline::test {

class HeadlessUi {
  public:
    explicit HeadlessUi(float width = 1600, float height = 1000) {
        m_context = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(width, height);
        io.IniFilename = nullptr;
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        // The same key indices as the GLFW back end.
        io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
        io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
        io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
        io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
        io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
        io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
        io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
        io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
        io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
        io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
        io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
        io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
        io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
        io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
        io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
        io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
        io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
        io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
    }
    ~HeadlessUi() { ImGui::DestroyContext(m_context); }
    HeadlessUi(const HeadlessUi&) = delete;
    HeadlessUi& operator=(const HeadlessUi&) = delete;

    double time() const { return m_time; }

    // Runs `n` frames; the commands emitted in them are appended to emitted().
    void frames(ui::Workbench& wb, int n = 1) {
        for (int k = 0; k < n; ++k) {
            ImGui::NewFrame();
            wb.frame(m_time);
            wb.renderViews(); // a no-op without a renderer
            ImGui::Render();
            for (const auto& c : wb.emittedThisFrame())
                m_emitted.push_back(c);
            m_time += 1.0 / 60.0;
            ImGuiIO& io = ImGui::GetIO();
            io.MouseWheel = 0;
            for (int key : m_releaseAfterFrame)
                io.KeysDown[key] = false;
            m_releaseAfterFrame.clear();
        }
    }
    // Frames until background work (opening, frame loads) is done: until two looks in a row
    // find no job and no frame loading, since work a frame starts (a surface built again once a
    // derived frame arrives, which the frame cache can hand over at once) shows only at the
    // next look.
    void settle(ui::Workbench& wb) {
        for (int k = 0, quiet = 0; k < 50 && quiet < 2; ++k) {
            wb.jobs().waitAll();
            wb.frames().waitIdle();
            frames(wb, 2);
            quiet = !wb.jobs().busy() && !wb.frames().loading() ? quiet + 1 : 0;
        }
        frames(wb, 2);
    }

    const std::vector<core::Json>& emitted() const { return m_emitted; }
    void clearEmitted() { m_emitted.clear(); }
    // The emitted commands with this op.
    std::vector<core::Json> emitted(const std::string& op) const {
        std::vector<core::Json> out;
        for (const auto& c : m_emitted)
            if (c.value("op", "") == op)
                out.push_back(c);
        return out;
    }

    ui::ItemRect rect(ui::Workbench& wb, const std::string& name) {
        auto r = wb.items().find(name);
        if (!r) {
            ADD_FAILURE() << "no widget marked \"" << name << "\" in the last frame";
            return {};
        }
        return *r;
    }
    bool has(ui::Workbench& wb, const std::string& name) const {
        return wb.items().find(name).has_value();
    }

    void moveTo(ui::Workbench& wb, float x, float y, int frameCount = 1) {
        ImGui::GetIO().MousePos = ImVec2(x, y);
        frames(wb, frameCount);
    }
    void button(ui::Workbench& wb, int button, bool down) {
        ImGui::GetIO().MouseDown[button] = down;
        frames(wb);
    }
    void click(ui::Workbench& wb, const std::string& name, int button = 0) {
        const ui::ItemRect r = rect(wb, name);
        clickAt(wb, r.cx(), r.cy(), button);
    }
    void clickAt(ui::Workbench& wb, float x, float y, int button = 0) {
        moveTo(wb, x, y);
        this->button(wb, button, true);
        this->button(wb, button, false);
    }
    // Presses at `from`, moves to `to` in steps (a frame each), releases.
    void drag(ui::Workbench& wb, float x0, float y0, float x1, float y1, int steps = 6,
              int button = 0, const std::function<void()>& whileHeld = {}) {
        moveTo(wb, x0, y0);
        this->button(wb, button, true);
        for (int k = 1; k <= steps; ++k)
            moveTo(wb, x0 + (x1 - x0) * k / steps, y0 + (y1 - y0) * k / steps);
        if (whileHeld)
            whileHeld();
        this->button(wb, button, false);
    }
    void key(ui::Workbench& wb, int key, bool ctrl = false, bool shift = false) {
        ImGuiIO& io = ImGui::GetIO();
        io.KeyCtrl = ctrl;
        io.KeyShift = shift;
        io.KeysDown[key] = true;
        m_releaseAfterFrame.push_back(key);
        frames(wb);
        io.KeyCtrl = io.KeyShift = false;
        frames(wb);
    }
    void type(ui::Workbench& wb, const std::string& text) {
        for (char c : text)
            ImGui::GetIO().AddInputCharacter(static_cast<unsigned>(c));
        frames(wb);
    }
    // Into the field marked `name`: one click, select all, type `text`, then press `finish`
    // (Enter commits, Escape cancels).
    void retype(ui::Workbench& wb, const std::string& name, const std::string& text,
                int finish = GLFW_KEY_ENTER) {
        click(wb, name);
        key(wb, GLFW_KEY_A, /*ctrl=*/true);
        type(wb, text);
        key(wb, finish);
    }
    void wheel(ui::Workbench& wb, float x, float y, float amount) {
        ImGui::GetIO().MousePos = ImVec2(x, y);
        ImGui::GetIO().MouseWheel = amount;
        frames(wb);
    }
    // Makes a panel's tab the active one (panels draw only when shown).
    void showPanel(ui::Workbench& wb, const std::string& panel) {
        wb.layout().setActive(panel);
        frames(wb, 2);
    }

  private:
    ImGuiContext* m_context = nullptr;
    double m_time = 1.0;
    std::vector<core::Json> m_emitted;
    std::vector<int> m_releaseAfterFrame;
};

// The lattice of lattice_dump.hpp, written to `path`.
inline std::string writeLattice(const std::string& path) {
    const std::string text = latticeDump();
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
    return path;
}

} // namespace faultline::test
