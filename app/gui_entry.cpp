// `faultline [PATH]`: the workbench on PATH (a data file, a pattern, or a *.faultline.json
// session), or on the demo model. Without a display it says which commands work headless.
#include "app/cli.hpp"

#include "core/session/session.hpp"
#ifdef FAULTLINE_WITH_GUI
#include "ui/app/gui_app.hpp"
#include "ui/display_probe.hpp"
#endif

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

namespace faultline::app {

namespace {

namespace fs = std::filesystem;

// XDG folders: the autosave and journals under state, recent files under config.
[[maybe_unused]] std::string xdgDir(const char* variable, const char* fallback) {
    if (const char* v = std::getenv(variable); v && *v)
        return (fs::path(v) / "faultline").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / fallback / "faultline").string();
    return {};
}

} // namespace

int runGui(const Args& argsIn) {
    // --screenshot PNG: once the data has loaded, save the window and quit (docs, checks).
    // --size WxH: the window size.
    Args args;
    std::string screenshot;
    int width = 1600, height = 1000;
    for (std::size_t k = 0; k < argsIn.size(); ++k) {
        if (argsIn[k] == "--screenshot" && k + 1 < argsIn.size())
            screenshot = argsIn[++k];
        else if (argsIn[k] == "--size" && k + 1 < argsIn.size() &&
                 std::sscanf(argsIn[++k].c_str(), "%dx%d", &width, &height) == 2 && width > 0 &&
                 height > 0)
            continue;
        else
            args.push_back(argsIn[k]);
    }
    if (args.size() > 1 || (!args.empty() && args.front().rfind("-", 0) == 0)) {
        std::fprintf(stderr, "faultline: unexpected arguments\n");
        printUsage();
        return 2;
    }
    std::string why = "this build has no GUI";
#ifdef FAULTLINE_WITH_GUI
    const bool display = ui::displayAvailable(why);
#else
    const bool display = false;
#endif
    if (!display) {
        std::fprintf(stderr,
                     "faultline: cannot open the workbench: %s.\n"
                     "These commands work without a display:\n"
                     "  faultline info PATH...         what a data file holds\n"
                     "  faultline replay JOURNAL.jsonl run a recorded analysis headless\n"
                     "Run `faultline --help` for details.\n",
                     why.c_str());
        return 1;
    }
#ifdef FAULTLINE_WITH_GUI
    core::Session session;
    registerAppOps(session);
    ui::GuiOptions options;
    options.width = width;
    options.height = height;
    options.maximize = screenshot.empty();
    options.workbench.stateDir = xdgDir("XDG_STATE_HOME", ".local/state");
    options.workbench.configDir = xdgDir("XDG_CONFIG_HOME", ".config");
    try {
        ui::GuiApp gui(session, std::move(options));
        const std::string path = args.empty() ? std::string() : args.front();
        if (path.empty())
            gui.workbench().opener().openDemo(); // made once (about a minute), then reused
        else
            gui.workbench().opener().openPath(path);
        if (screenshot.empty())
            return gui.run();
        // Settle: the data opened, its frame shown, a few frames drawn.
        int quiet = 0;
        for (int k = 0; k < 200000 && quiet < 10 && gui.step(true); ++k) {
            auto& wb = gui.workbench();
            const bool busy =
                wb.jobs().busy() || wb.frames().loading() || (!wb.dataset() && k < 2000);
            quiet = busy ? 0 : quiet + 1;
        }
        gui.workbench().requestScreenshot(screenshot); // taken before the next swap
        gui.step();
        if (!fs::exists(screenshot)) {
            std::fprintf(stderr, "faultline: cannot write %s\n", screenshot.c_str());
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline: %s\n", e.what());
        return 1;
    }
#else
    return 1;
#endif
}

} // namespace faultline::app
