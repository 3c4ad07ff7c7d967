// Issue 42: a soak test. The workbench driven at random, with a fixed seed, as a user would:
// clicks on whatever widgets the last frame drew (buttons, tabs, checkboxes, list rows, menus'
// items), drags and wheel turns in the views, key chords (undo, redo, frame steps, Escape),
// typing into whatever field has focus. After every batch of actions the background work is
// let finish and what users rely on is checked:
// - the session saves and opens again as the same state;
// - undo all, then redo all, gives the same state;
// - the autosave file opens as a session.
// - the views draw with OpenGL (every FAULTLINE_SOAK_GL_EVERY checks, default 4: every 200
//   actions) with no GL error (strict checks: FAULTLINE_GL_CHECKS=1, as the test command
//   sets), where a context can be had (under the test command, FAULTLINE_REQUIRE_GL=1, it must).
// FAULTLINE_SOAK_ACTIONS (default 20000, under a minute) and FAULTLINE_SOAK_SEED (default 1)
// set the run. Between checks the views are not drawn (their input is handled);
// scripts/soak.sh runs it long. A failure names the seed and the action, so it reproduces.
#include <epoxy/gl.h> // before GLFW's GL/gl.h

#include "gl_required.hpp"
#include "panel_fixture.hpp"

#include "core/session/session_json.hpp"
#include "ui/render/offscreen.hpp"
#include "ui/viewport/gl_view_renderer.hpp"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdlib>
#include <execinfo.h>
#include <filesystem>
#include <map>
#include <new>
#include <random>
#include <sstream>
#include <unistd.h>

using namespace faultline;
using namespace faultline::test;
using core::Json;

namespace {

long long envNumber(const char* name, long long fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::atoll(v) : fallback;
}

std::string stateOf(const core::Session& s) { return core::sessionToJson(s.state(), "").dump(); }

// Widgets a random click must not press: quitting ends the run, and the file dialog's own
// buttons would write or open files anywhere (the dialog is closed with Escape instead).
bool offLimits(const std::string& name) {
    for (const char* bad : {"quit", "dialog.", "file."})
        if (name.find(bad) != std::string::npos)
            return true;
    return false;
}

// Seen once under a loaded parallel CTest run and never reproduced since: std::bad_alloc out of
// the random use. A failed allocation prints where it came from before it throws, so the next
// occurrence names its allocation, not only the seed.
void reportFailedAllocation() {
    static const char kSay[] = "soak: an allocation failed; the stack:\n";
    [[maybe_unused]] const auto said = write(2, kSay, sizeof(kSay) - 1);
    void* frames[64];
    backtrace_symbols_fd(frames, backtrace(frames, 64), 2);
    std::set_new_handler(nullptr); // the next attempt throws std::bad_alloc
}

class Soak : public PanelTest {
  protected:
    std::string stateDir() override { return dir.file("state"); }
};

} // namespace

TEST_F(Soak, RandomUseKeepsTheSessionSound) {
    const long long actions = envNumber("FAULTLINE_SOAK_ACTIONS", 20000);
    const auto seed = static_cast<std::uint32_t>(envNumber("FAULTLINE_SOAK_SEED", 1));
    const auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(dir.path()); // whatever a dialog writes lands here
    openLattice();
    session.apply({{"op", "threshold.add"}, {"variable", "strain"}, {"low", 0.5}, {"high", 1e30}});
    session.apply({{"op", "fault.create"}, {"name", "F1"}, {"ids", {2, 6, 10, 14}}});
    headless.settle(wb());

    // The views' OpenGL renderer, used at the checks (llvmpipe draws too slowly for every
    // frame of a fast random run).
    std::string noGl;
    std::unique_ptr<ui::GlViewRenderer> gl;
    if (ui::sharedOffscreenContext(noGl))
        gl = std::make_unique<ui::GlViewRenderer>(ui::RendererBackend::OpenGL);
    else if (const char* required = std::getenv("FAULTLINE_REQUIRE_GL");
             required && *required == '1')
        FAIL() << "no OpenGL context: " << noGl << " (FAULTLINE_REQUIRE_GL=1)";
    const long long glEvery = std::max(1LL, envNumber("FAULTLINE_SOAK_GL_EVERY", 4));
    long long checks = 0, drawn = 0;

    const std::new_handler previousHandler = std::set_new_handler(reportFailedAllocation);
    std::mt19937 rng(seed);
    auto pick = [&](std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
    };
    const int keys[] = {GLFW_KEY_Z,    GLFW_KEY_Y,      GLFW_KEY_LEFT,   GLFW_KEY_RIGHT,
                        GLFW_KEY_HOME, GLFW_KEY_END,    GLFW_KEY_ESCAPE, GLFW_KEY_ENTER,
                        GLFW_KEY_TAB,  GLFW_KEY_DELETE, GLFW_KEY_F,      GLFW_KEY_1,
                        GLFW_KEY_2};
    std::ostringstream log; // the last actions, for a failure's message
    std::size_t counts[6] = {};
    const auto start = std::chrono::steady_clock::now();

    auto check = [&](long long at) {
        // Dialogs and popups closed, background work done.
        headless.key(wb(), GLFW_KEY_ESCAPE);
        headless.settle(wb());
        const std::string now = stateOf(session);
        const std::string saved = dir.file("soak.faultline.json");
        session.apply({{"op", "session.save"}, {"path", saved}});
        core::Session reopened;
        reopened.apply({{"op", "session.open"}, {"path", saved}});
        ASSERT_EQ(stateOf(reopened), now) << "seed " << seed << ", after action " << at
                                          << ": the saved session opened differently\n"
                                          << log.str();
        std::size_t undone = 0;
        while (session.undo())
            ++undone;
        for (std::size_t k = 0; k < undone; ++k)
            ASSERT_TRUE(session.redo()) << "seed " << seed << ", after action " << at;
        ASSERT_EQ(stateOf(session), now) << "seed " << seed << ", after action " << at
                                         << ": undo all + redo all changed the state\n"
                                         << log.str();
        EXPECT_FALSE(session.modified()) << "seed " << seed << ", after action " << at
                                         << ": back at the saved state, yet unsaved";
        headless.frames(wb(), 2);
        if (gl && ++checks % glEvery == 0) {
            // Every view drawn as the workbench draws it, and OpenGL reports no error.
            ui::sharedOffscreenContext(noGl); // current on this thread
            wb().setRenderer(gl.get());
            try {
                headless.frames(wb(), 2);
            } catch (const std::exception& e) {
                ADD_FAILURE() << "seed " << seed << ", after action " << at
                              << ": drawing the views failed: " << e.what() << "\n"
                              << log.str();
            }
            wb().setRenderer(nullptr);
            const GLenum error = glGetError();
            EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << "seed " << seed << ", after action " << at
                                                  << ": GL error 0x" << std::hex << error << "\n"
                                                  << log.str();
            ++drawn;
        }
        const std::string recovery = dir.file("state/recovery.faultline.json");
        if (std::filesystem::exists(recovery)) {
            core::Session fromAutosave;
            EXPECT_NO_THROW(fromAutosave.apply({{"op", "session.open"}, {"path", recovery}}))
                << "seed " << seed << ", after action " << at << ": the autosave does not open";
        }
        if (!session.dataset()) // a random "Close data": open it again to keep going
            openLattice();
        log.str("");
    };

    for (long long a = 0; a < actions; ++a)
        try {
            const auto& items = wb().items().all();
            std::vector<std::pair<std::string, ui::ItemRect>> targets;
            for (const auto& [name, r] : items)
                if (!offLimits(name) && r.x1 > r.x0 && r.y1 > r.y0)
                    targets.emplace_back(name, r);
            const std::size_t kind = pick(10);
            if (kind < 5 && !targets.empty()) { // a click on a widget
                const auto& [name, r] = targets[pick(targets.size())];
                log << a << ": click " << name << "\n";
                headless.clickAt(wb(), r.cx(), r.cy());
                ++counts[0];
            } else if (kind < 7) { // a drag in a view, any button
                if (auto v = wb().items().find("view.image.main")) {
                    const float x0 = v->x0 + float(pick(100)) / 100 * (v->x1 - v->x0);
                    const float y0 = v->y0 + float(pick(100)) / 100 * (v->y1 - v->y0);
                    const int button = int(pick(3));
                    log << a << ": drag button " << button << "\n";
                    headless.drag(wb(), x0, y0, x0 + float(pick(200)) - 100,
                                  y0 + float(pick(200)) - 100, 4, button);
                }
                ++counts[1];
            } else if (kind < 9) { // a key, maybe with Ctrl / Shift
                const int key = keys[pick(std::size(keys))];
                const bool ctrl = pick(2) == 0, shift = pick(3) == 0;
                if (ctrl && (key == GLFW_KEY_Q || key == GLFW_KEY_W))
                    continue;
                log << a << ": key " << key << (ctrl ? " ctrl" : "") << (shift ? " shift" : "")
                    << "\n";
                headless.key(wb(), key, ctrl, shift);
                ++counts[2];
            } else if (pick(2)) { // typing into whatever has focus
                log << a << ": type\n";
                headless.type(wb(), std::to_string(pick(40)) + (pick(2) ? "." : ""));
                ++counts[3];
            } else { // the wheel over the main view
                if (auto v = wb().items().find("view.image.main"))
                    headless.wheel(wb(), v->cx(), v->cy(), pick(2) ? 1.0f : -1.0f);
                ++counts[4];
            }
            headless.frames(wb(), 1 + int(pick(3)));
            if ((a + 1) % 50 == 0 || a + 1 == actions) {
                check(a);
                if (HasFatalFailure())
                    break;
            }
        } catch (const std::exception& e) {
            ADD_FAILURE() << "seed " << seed << ", action " << a << ": " << e.what() << "\n"
                          << log.str();
            break;
        }
    std::set_new_handler(previousHandler);
    std::map<std::string, int> ops; // what the random use did to the session
    for (const Json& cmd : session.journal())
        if (cmd.is_object() && cmd.contains("op"))
            ++ops[cmd["op"].get<std::string>()];
    std::string opsText;
    for (const auto& [op, n] : ops)
        opsText += " " + op + " " + std::to_string(n);
    std::printf("soak: journal of %zu commands:%s\n", session.journal().size(), opsText.c_str());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("soak: seed %u, %lld actions (clicks %zu, drags %zu, keys %zu, typing %zu, "
                "wheel %zu) in %.1f s: %.0f actions per minute; views drawn with %s %lld times\n",
                seed, actions, counts[0], counts[1], counts[2], counts[3], counts[4], seconds,
                60.0 * double(actions) / std::max(seconds, 1e-9), gl ? "OpenGL" : "no OpenGL",
                drawn);
    std::filesystem::current_path(cwd);
}
