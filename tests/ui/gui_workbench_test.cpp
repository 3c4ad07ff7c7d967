// The workbench in a real window (GLFW, OpenGL, under Xvfb in CI) driven by synthetic input fed
// to ImGui after the devices are read: drop a data file, add a box, drag a threshold on a
// histogram, undo, save the session through the file dialog, take a screenshot. Skipped when
// there is no display.
#include "../core/test_files.hpp"
#include "gl_required.hpp"

#include "core/session/session.hpp"
#include "ui/app/gui_app.hpp"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <stb_image.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace faultline;
using core::Json;
using faultline::test::TempDir;

namespace {

// What the synthetic devices report this frame.
struct SyntheticInput {
    ImVec2 mouse{10, 10};
    bool down[3] = {false, false, false};
    std::set<int> keys;
    bool ctrl = false, shift = false;
    std::string text;
    void apply(ImGuiIO& io) {
        io.MousePos = mouse;
        for (int b = 0; b < 3; ++b)
            io.MouseDown[b] = down[b];
        for (int k = 0; k < 512; ++k)
            io.KeysDown[k] = keys.count(k) > 0;
        io.KeyCtrl = ctrl;
        io.KeyShift = shift;
        for (char c : text)
            io.AddInputCharacter(static_cast<unsigned>(c));
        text.clear();
    }
};

class Driver {
  public:
    Driver(ui::GuiApp& app) : m_app(app) {
        app.setInputHook([this](ImGuiIO& io) { m_input.apply(io); });
    }
    ui::Workbench& wb() { return m_app.workbench(); }
    void steps(int n = 1) {
        for (int k = 0; k < n; ++k)
            m_app.step(false);
    }
    void settle() {
        for (int k = 0; k < 400; ++k) {
            steps();
            if (!wb().jobs().busy() && !wb().frames().loading() && k > 3)
                break;
        }
        steps(3);
    }
    ui::ItemRect rect(const std::string& name) {
        auto r = wb().items().find(name);
        EXPECT_TRUE(r) << "no widget \"" << name << "\" on screen";
        return r.value_or(ui::ItemRect{});
    }
    void moveTo(float x, float y) {
        m_input.mouse = ImVec2(x, y);
        steps(2);
    }
    void click(const std::string& name) {
        const ui::ItemRect r = rect(name);
        moveTo(r.cx(), r.cy());
        m_input.down[0] = true;
        steps();
        m_input.down[0] = false;
        steps(2);
    }
    void drag(float x0, float y0, float x1, float y1, int n = 8) {
        moveTo(x0, y0);
        m_input.down[0] = true;
        steps();
        for (int k = 1; k <= n; ++k)
            moveTo(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n);
        m_input.down[0] = false;
        steps(2);
    }
    void press(bool down) { // the left button, where the mouse is
        m_input.down[0] = down;
        steps(2);
    }
    void key(int k, bool ctrl = false, bool shift = false) {
        m_input.ctrl = ctrl;
        m_input.shift = shift;
        m_input.keys.insert(k);
        steps();
        m_input.keys.erase(k);
        m_input.ctrl = m_input.shift = false;
        steps(2);
    }
    void type(const std::string& text) {
        m_input.text = text;
        steps(2);
    }

  private:
    ui::GuiApp& m_app;
    SyntheticInput m_input;
};

// The real window (1600 x 1000, not maximised) on `session`; null when this machine has no
// OpenGL window to give (the caller skips).
std::unique_ptr<ui::GuiApp> openWindow(core::Session& session, const std::string& stateDir,
                                       std::string& why) {
    ui::GuiOptions options;
    options.width = 1600;
    options.height = 1000;
    options.maximize = false;
    options.workbench.stateDir = stateDir;
    try {
        return std::make_unique<ui::GuiApp>(session, options);
    } catch (const std::exception& e) {
        why = e.what();
        return nullptr;
    }
}

// The real window with the LIGGGHTS packing dropped on it and loaded; null (`why` says) when
// there is no display or no OpenGL window.
std::unique_ptr<ui::GuiApp> windowOnThePacking(core::Session& session, std::string& why) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        why = "no display (run under xvfb-run for this test)";
        return nullptr;
    }
    std::unique_ptr<ui::GuiApp> app = openWindow(session, "", why);
    if (!app) {
        why = "no OpenGL window here: " + why;
        return nullptr;
    }
    Driver ui(*app);
    ui.steps(3);
    app->dropFiles({test::dataFile("liggghts_packing_22410.particles")});
    ui.settle();
    return app;
}

// In a test body (it skips or fails the test without a window): `app` and its Driver `driver`,
// the packing loaded into `session`.
#define FAULTLINE_WINDOW_ON_THE_PACKING(app, driver, session)                                      \
    std::string app##Why;                                                                          \
    std::unique_ptr<ui::GuiApp> app = windowOnThePacking(session, app##Why);                       \
    if (!app)                                                                                      \
        FAULTLINE_NEED_GL(app##Why);                                                               \
    Driver driver(*app);                                                                           \
    ASSERT_NE(session.dataset(), nullptr) << driver.wb().lastMessage()

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(Gui, DrivesTheRealWindowThroughAnAnalysis) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display)
        FAULTLINE_NEED_GL("no display (run under xvfb-run for this test)");
    TempDir dir;
    core::Session session;
    std::string why;
    std::unique_ptr<ui::GuiApp> app = openWindow(session, dir.file("state"), why);
    if (!app)
        FAULTLINE_NEED_GL("no OpenGL window here: " << why);
    Driver ui(*app);
    ui.steps(3);

    // 1. Open data by dropping a file on the window.
    const std::string data = test::dataFile("liggghts_packing_22410.particles");
    app->dropFiles({data});
    ui.settle();
    ASSERT_NE(session.dataset(), nullptr) << ui.wb().lastMessage();
    const ui::ViewDisplay* main = ui.wb().mainDisplay();
    ASSERT_TRUE(main && main->visibility);
    EXPECT_EQ(main->visibility->visibleCount, 22410u);

    // 2. Add a box in the Cutting boxes panel.
    ui.click("tab.boxes");
    ui.click("boxes.add");
    ASSERT_EQ(session.state().boxes.size(), 1u);
    EXPECT_EQ(session.state().boxes[0].name, "box 1");

    // 3. Drag across the vx histogram: a threshold on vx.
    const ui::ItemRect h = ui.rect("histogram.vx");
    ui.drag(h.x0 + (h.x1 - h.x0) * 0.55f, h.cy(), h.x1 - 2, h.cy());
    ASSERT_NE(session.state().threshold("vx"), nullptr);
    const std::size_t visibleWithThreshold = ui.wb().mainDisplay()->visibility->visibleCount;
    EXPECT_LT(visibleWithThreshold, 22410u);
    EXPECT_GT(visibleWithThreshold, 0u);

    // 4. Undo (Ctrl+Z) removes the threshold, keeps the box.
    ui.key(GLFW_KEY_Z, true);
    EXPECT_EQ(session.state().threshold("vx"), nullptr);
    EXPECT_EQ(session.state().boxes.size(), 1u);
    EXPECT_EQ(ui.wb().mainDisplay()->visibility->visibleCount, 22410u);

    // 5. Save (Ctrl+S): the session has no file yet, so the dialog asks; type a path, Enter.
    const std::string saved = dir.file("gui-analysis.faultline.json");
    ui.key(GLFW_KEY_S, true);
    ASSERT_TRUE(ui.wb().fileDialog().isOpen());
    ui.key(GLFW_KEY_A, true); // select the suggested name, then replace it
    ui.type(saved);
    const char* keep = std::getenv("FAULTLINE_GUI_TEST_KEEP");
    if (keep && *keep) { // how the dialog looks, for a person to judge
        ui.wb().requestScreenshot(std::string(keep) + "/gui-test-dialog.png");
        ui.steps(1);
    }
    ui.key(GLFW_KEY_ENTER);
    ui.steps(2);
    ASSERT_TRUE(std::filesystem::exists(saved)) << ui.wb().lastMessage();
    const Json doc = Json::parse(readFile(saved));
    ASSERT_EQ(doc["boxes"].size(), 1u);
    EXPECT_EQ(doc["boxes"][0]["name"], "box 1");
    EXPECT_TRUE(doc["thresholds"].empty());
    EXPECT_EQ(doc["data"].dump().find("liggghts_packing_22410.particles") != std::string::npos,
              true)
        << doc.dump();
    EXPECT_TRUE(doc["dock_layout"].contains("root"));
    EXPECT_EQ(ui.wb().sessionPath(), saved);

    // 6. A screenshot of the window.
    const std::string shot = dir.file("workbench.png");
    ui.wb().requestScreenshot(shot);
    ui.steps(1);
    int w = 0, hgt = 0, c = 0;
    unsigned char* pixels = stbi_load(shot.c_str(), &w, &hgt, &c, 4);
    ASSERT_NE(pixels, nullptr) << "no PNG at " << shot;
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(app->window(), &fbw, &fbh);
    EXPECT_EQ(w, fbw);
    EXPECT_EQ(hgt, fbh);
    std::set<std::uint32_t> colours;
    for (int k = 0; k < w * hgt; k += 97)
        colours.insert(reinterpret_cast<std::uint32_t*>(pixels)[k]);
    stbi_image_free(pixels);
    EXPECT_GT(colours.size(), 20u) << "the screenshot looks blank";
    if (keep && *keep) {
        std::filesystem::copy_file(shot, std::string(keep) + "/gui-test.png",
                                   std::filesystem::copy_options::overwrite_existing);
        std::filesystem::copy_file(ui.wb().journalPath(), std::string(keep) + "/gui-test.jsonl",
                                   std::filesystem::copy_options::overwrite_existing);
    }

    // The journal of the run holds every step as a command.
    std::vector<std::string> ops;
    std::istringstream journal(readFile(ui.wb().journalPath()));
    for (std::string line; std::getline(journal, line);)
        if (!line.empty() && line[0] == '{')
            ops.push_back(Json::parse(line)["op"].get<std::string>());
    EXPECT_EQ(ops, (std::vector<std::string>{"data.open", "box.add", "threshold.add", "undo",
                                             "layout.set", "session.save"}));
}

TEST(Gui, LassoInTheRealWindowMakesAFaultAndItsMetricsArePlotted) {
    core::Session session;
    FAULTLINE_WINDOW_ON_THE_PACKING(app, ui, session);

    // The lasso tool; a loop around the middle of the view, drawn while the button is held.
    ui.click("viewports.tool.lasso");
    ASSERT_EQ(ui.wb().selection().tool, ui::ViewportTool::Lasso);
    const ui::ItemRect img = ui.rect("view.image.main");
    const float cx = img.cx(), cy = img.cy(), r = 0.12f * (img.y1 - img.y0);
    ui.moveTo(cx + r, cy);
    ui.press(true);
    for (int k = 1; k <= 24; ++k)
        ui.moveTo(cx + r * std::cos(k * 0.25f), cy + r * std::sin(k * 0.25f) * 0.7f);
    const char* keep = std::getenv("FAULTLINE_GUI_TEST_KEEP");
    if (keep && *keep) { // the outline while drawing, for a person to judge
        ui.wb().requestScreenshot(std::string(keep) + "/gui-test-lasso.png");
        ui.steps(1);
    }
    ui.press(false);
    ASSERT_EQ(session.state().faults.size(), 1u) << ui.wb().lastMessage();
    const core::Fault& f = session.state().faults[0];
    EXPECT_EQ(f.name, "F1");
    EXPECT_GT(f.ids.size(), 50u);
    EXPECT_LT(f.ids.size(), 22410u);
    EXPECT_EQ(ui.wb().selection().faults, std::set<std::string>{"F1"});

    // Its metrics, in the Faults panel.
    ui.click("tab.faults");
    ui.settle();
    EXPECT_TRUE(ui.wb().items().find("faults.metrics.plot").has_value());
    if (keep && *keep) {
        ui.wb().requestScreenshot(std::string(keep) + "/gui-test-fault.png");
        ui.steps(1);
    }
}

// Issue 27: an idle workbench presents nothing new. Frames whose draw lists match the picture on
// screen (and no view drawn again) are neither drawn nor presented; a change is at once.
TEST(Gui, AnIdleWindowPresentsNoFramesUntilSomethingChanges) {
    core::Session session;
    FAULTLINE_WINDOW_ON_THE_PACKING(app, ui, session);
    for (int k = 0; k < 8; ++k) // settle: tooltips, fades, first view draws
        app->step(true);
    const std::size_t presented = app->presentedFrames(), skipped = app->skippedFrames();
    for (int k = 0; k < 6; ++k) // idle: each waits at most a quarter second
        app->step(true);
    EXPECT_EQ(app->presentedFrames(), presented);
    EXPECT_EQ(app->skippedFrames(), skipped + 6);
    // A change shows at once.
    session.apply(
        core::Json::parse(R"({"op":"threshold.add","variable":"z","low":0,"high":0.01})"));
    app->step(true);
    app->step(true);
    EXPECT_GT(app->presentedFrames(), presented);
}
