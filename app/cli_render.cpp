// `faultline render SESSION_OR_JOURNAL --out figure.png [--view NAME] [--frame N]
//  [--size WxH] [--transparent] [--data PATH...]`: a figure without showing a window.
#include "app/cli.hpp"

#include "core/io/input_error.hpp"
#include "core/session/journal.hpp"
#include "core/session/session_json.hpp"

#if FAULTLINE_WITH_GUI
#include "ui/viewport/session_figure.hpp"
#endif

#include <cstdio>
#include <filesystem>

namespace faultline::app {

int runRender(const Args& args) {
#if !FAULTLINE_WITH_GUI
    (void)args;
    std::fprintf(stderr,
                 "faultline render: this build has no renderer (FAULTLINE_BUILD_GUI=OFF)\n");
    return 2;
#else
    const char* usage =
        "usage: faultline render SESSION.faultline.json|JOURNAL.jsonl --out FIGURE.png\n"
        "         [--view NAME] [--frame N] [--size WxH] [--transparent] [--data PATH...]\n"
        "Without a display (DISPLAY unset) OpenGL comes from EGL: no X server is needed.";
    std::string input;
    std::vector<std::string> data;
    ui::FigureRequest request;
    for (std::size_t k = 0; k < args.size(); ++k) {
        const std::string& a = args[k];
        auto value = [&]() -> std::string {
            if (k + 1 >= args.size())
                throw std::invalid_argument(a + " needs a value");
            return args[++k];
        };
        if (a == "--out")
            request.path = value();
        else if (a == "--view")
            request.view = value();
        else if (a == "--frame")
            request.frame = static_cast<std::size_t>(std::stoul(value()));
        else if (a == "--size") {
            const std::string s = value();
            if (std::sscanf(s.c_str(), "%dx%d", &request.width, &request.height) != 2) {
                std::fprintf(stderr, "faultline render: --size takes WIDTHxHEIGHT, found '%s'\n",
                             s.c_str());
                return 2;
            }
        } else if (a == "--transparent")
            request.transparent = true;
        else if (a == "--data") {
            while (k + 1 < args.size() && args[k + 1].rfind("--", 0) != 0)
                data.push_back(std::filesystem::absolute(args[++k]).string());
        } else if (input.empty() && a.rfind("--", 0) != 0)
            input = a;
        else {
            std::fprintf(stderr, "faultline render: unexpected argument '%s'\n%s\n", a.c_str(),
                         usage);
            return 2;
        }
    }
    if (input.empty() || request.path.empty()) {
        std::fprintf(stderr, "%s\n", usage);
        return 2;
    }
    core::Session session;
    registerAppOps(session);
    try {
        if (input.size() > 6 && input.compare(input.size() - 6, 6, ".jsonl") == 0) {
            core::ReplayOptions options;
            options.data = data;
            options.outDir = std::filesystem::absolute(std::filesystem::path(request.path))
                                 .parent_path()
                                 .string();
            const auto report = core::replayJournal(input, options, session);
            for (const auto& f : report.failures)
                std::fprintf(stderr, "%s:%zu: %s\n", input.c_str(), f.line, f.message.c_str());
            if (report.stopped)
                return 1;
        } else {
            core::SessionState state = core::loadSessionFile(input);
            if (!data.empty())
                state.dataPaths = data; // the session's data moved: --data says where
            session.replaceState(std::move(state));
        }
        ui::renderSessionFigure(session, request);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline render: %s\n", e.what());
        return 1;
    }
    std::printf("%s\n", request.path.c_str());
    return 0;
#endif
}

} // namespace faultline::app
