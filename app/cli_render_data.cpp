// `faultline render-data FILE --out x.png [...]`: a developer's way to render a data file to a
// PNG offscreen until `faultline render SESSION_OR_JOURNAL` lands with sessions.
#include "app/cli.hpp"

#include "core/data/dataset.hpp"
#include "core/io/input_error.hpp"
#include "core/selection/column_view.hpp"
#include "core/selection/cutting_box.hpp"

#if FAULTLINE_WITH_GUI
#include "ui/render/offscreen.hpp"
#endif

#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace faultline::app {

namespace {

[[maybe_unused]] std::vector<double> parseNumbers(const std::string& text, char sep,
                                                  std::size_t count, const std::string& option) {
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, sep)) {
        try {
            std::size_t used = 0;
            out.push_back(std::stod(item, &used));
            if (used != item.size())
                throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw std::invalid_argument(option + ": '" + item + "' is not a number");
        }
    }
    if (out.size() != count)
        throw std::invalid_argument(option + " needs " + std::to_string(count) + " numbers");
    return out;
}

[[maybe_unused]] const char* kUsage =
    "usage: faultline render-data FILE --out OUT.png [--frame N] [--color VAR] [--map NAME]\n"
    "         [--range LO,HI] [--size WxH] [--view front|back|left|side|top|bottom|iso] [--ortho]\n"
    "         [--zoom F]\n"
    "         [--transparent] [--supersample 1..4] [--context] [--no-ao]\n"
    "         [--threshold VAR:LO:HI]... [--cut XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX]...\n"
    "Renders one frame of a data file offscreen (without a display, through EGL).\n"
    "Maps: blue-red viridis diverging pastel bands bands:N gray";

} // namespace

int runRenderData(const Args& args) {
#if !FAULTLINE_WITH_GUI
    (void)args;
    std::fprintf(stderr,
                 "faultline render-data: this build has no renderer (FAULTLINE_BUILD_GUI=OFF)\n");
    return 2;
#else
    std::string input, out, color, view = "iso";
    std::size_t frameIndex = 0;
    ui::SceneDescription scene;
    ui::RenderSettings settings;
    bool ortho = false;
    double zoom = 1.0;
    std::vector<core::CuttingBox> cuts;
    struct Threshold {
        std::string variable;
        double low, high;
    };
    std::vector<Threshold> thresholds;
    try {
        for (std::size_t i = 0; i < args.size(); ++i) {
            const std::string& a = args[i];
            auto value = [&]() -> const std::string& {
                if (i + 1 >= args.size())
                    throw std::invalid_argument(a + " needs a value");
                return args[++i];
            };
            if (a == "--out") {
                out = value();
            } else if (a == "--frame") {
                frameIndex = static_cast<std::size_t>(std::stoul(value()));
            } else if (a == "--color") {
                color = value();
            } else if (a == "--map") {
                const std::string& name = value();
                auto map = core::parseColorMap(name);
                if (!map)
                    throw std::invalid_argument("unknown colour map '" + name + "'");
                scene.colorMap = *map;
            } else if (a == "--range") {
                const auto r = parseNumbers(value(), ',', 2, a);
                scene.colorRange = core::ValueRange{r[0], r[1]};
            } else if (a == "--size") {
                const auto s = parseNumbers(value(), 'x', 2, a);
                settings.width = static_cast<int>(s[0]);
                settings.height = static_cast<int>(s[1]);
            } else if (a == "--view") {
                view = value();
            } else if (a == "--zoom") {
                zoom = std::stod(value());
                if (!(zoom > 0.0))
                    throw std::invalid_argument("--zoom must be positive");
            } else if (a == "--ortho") {
                ortho = true;
            } else if (a == "--transparent") {
                settings.transparent = true;
            } else if (a == "--supersample") {
                settings.supersample = std::stoi(value());
            } else if (a == "--context") {
                scene.style.contextPoints = true;
            } else if (a == "--no-ao") {
                scene.style.ambientOcclusion = false;
            } else if (a == "--cut") {
                const auto b = parseNumbers(value(), ',', 6, a);
                cuts.push_back(
                    {"cut", {b[0], b[1], b[2]}, {b[3], b[4], b[5]}, core::BoxMode::Cut, true});
            } else if (a == "--threshold") {
                const std::string& t = value();
                const auto colon = t.find(':');
                if (colon == std::string::npos)
                    throw std::invalid_argument("--threshold needs VAR:LO:HI");
                const auto r = parseNumbers(t.substr(colon + 1), ':', 2, a);
                thresholds.push_back({t.substr(0, colon), r[0], r[1]});
            } else if (a == "-h" || a == "--help") {
                std::puts(kUsage);
                return 0;
            } else if (!a.empty() && a[0] == '-') {
                throw std::invalid_argument("unknown option " + a);
            } else if (input.empty()) {
                input = a;
            } else {
                throw std::invalid_argument("one input file only");
            }
        }
        if (input.empty() || out.empty())
            throw std::invalid_argument("an input file and --out are needed");
        if (settings.width <= 0 || settings.height <= 0 || settings.width > 16384 ||
            settings.height > 16384)
            throw std::invalid_argument("--size must be between 1x1 and 16384x16384");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline render-data: %s\n%s\n", e.what(), kUsage);
        return 2;
    }

    try {
        auto dataset = core::Dataset::open({input});
        if (frameIndex >= dataset->frameCount())
            throw std::invalid_argument("frame " + std::to_string(frameIndex) + " of " +
                                        std::to_string(dataset->frameCount()));
        const auto frame = dataset->frame(frameIndex);
        scene.frame = frame.get();
        scene.colorVariable = color;
        scene.boxes.clear();
        if (!cuts.empty() || !thresholds.empty()) {
            scene.visible.assign(frame->size(), 1);
            for (const core::CuttingBox& box : cuts) {
                for (std::size_t i = 0; i < frame->size(); ++i)
                    if (box.contains(frame->x[i], frame->y[i], frame->z[i]))
                        scene.visible[i] = 0;
                scene.boxes.push_back({{box.min[0], box.min[1], box.min[2]},
                                       {box.max[0], box.max[1], box.max[2]},
                                       {0.85f, 0.2f, 0.15f}});
            }
            for (const Threshold& t : thresholds) {
                const auto column = core::findColumn(*frame, t.variable); // x, y, z too
                if (!column)
                    throw std::invalid_argument("no variable '" + t.variable + "'");
                for (std::size_t i = 0; i < frame->size(); ++i) {
                    const double v = column->value(i);
                    if (!(v >= t.low && v <= t.high))
                        scene.visible[i] = 0;
                }
            }
        }
        const auto preset = core::parseViewPreset(view);
        if (!preset)
            throw std::invalid_argument("unknown view '" + view + "'");
        core::Camera camera = ui::fittedCamera(scene, settings.width, settings.height, *preset);
        if (ortho)
            camera.projection = core::Projection::Orthographic;
        camera.distance /= zoom;
        scene.camera = camera;
        const auto t0 = std::chrono::steady_clock::now();
        ui::renderSceneToPng(scene, settings, out);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        std::printf("%s: %zu spheres, %dx%d, %.0f ms\n", out.c_str(), frame->size(), settings.width,
                    settings.height, ms);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "faultline render-data: %s\n", e.what());
        return 1;
    }
#endif
}

} // namespace faultline::app
