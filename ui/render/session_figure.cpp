#include "ui/render/session_figure.hpp"

#include "core/color/colormap.hpp"
#include "core/model/frame_difference.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/fault_surface_request.hpp"
#include "ui/render/surface_mesh.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/render/legend_layout.hpp"
#include "ui/render/offscreen.hpp"
#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

namespace faultline::ui {

using core::CommandError;
using core::Json;

void renderSessionFigure(core::Session& session, const FigureRequest& request) {
    const core::ViewState* view = session.state().view(request.view);
    if (!view)
        throw CommandError("render: no view named \"" + request.view + "\"");
    auto dataset = session.dataset();
    if (!dataset)
        throw CommandError("render: no data is open");
    if (request.width < 16 || request.height < 16 || request.width > 16384 || request.height > 16384)
        throw CommandError("render: size must lie between 16x16 and 16384x16384");
    const std::size_t frameIndex = request.frame ? *request.frame : session.frameOfView(*view);
    if (frameIndex >= dataset->frameCount())
        throw CommandError("render: frame " + std::to_string(frameIndex) + " out of range 0.." +
                           std::to_string(dataset->frameCount() - 1));
    const auto frame = dataset->frame(frameIndex);

    SceneDescription scene;
    scene.frame = frame.get();
    const auto rowMask = session.faultRowMask(*frame);
    core::VisibilityResult visibility = core::computeVisibility(
        *frame, session.state().boxes, session.state().thresholds, rowMask.get());
    scene.visible = visibility.mask;
    scene.colorVariable = view->colorVariable;
    scene.style.contextPoints = view->contextPoints;
    if (auto map = core::parseColorMap(view->colorMap))
        scene.colorMap = *map;
    // Difference colouring: the change since the view's reference frame, matched by id.
    std::optional<core::AttributeColumn> difference;
    CategoryColoring categories; // "faults": each member in its fault's colour
    if (view->colorVariable == kFaultsVariable && !frame->attribute(kFaultsVariable)) {
        categories = faultColoring(*frame, session.state().faults);
        scene.colorColumn = categories.values.get();
        scene.colorMap = core::ColorMapSpec{core::ColorMapKind::Palette, 10, categories.palette};
        scene.colorRange = core::ValueRange{0.0, double(categories.palette.size())};
        scene.style.showLegend = false;
    } else if (view->difference.mode != core::ColorDifference::Mode::None) {
        const std::size_t ref = core::referenceFrame(*view, frameIndex, dataset->frameCount());
        const auto refFrame = dataset->frame(ref);
        try {
            difference = view->difference.mode == core::ColorDifference::Mode::Change
                             ? core::variableChange(*frame, *refFrame, view->colorVariable)
                             : core::displacementSince(*frame, *refFrame);
        } catch (const std::invalid_argument& e) {
            throw CommandError(std::string("render: ") + e.what());
        }
        scene.colorVariable = core::colorTitle(*view, ref);
        scene.colorColumn = &*difference;
        if (view->rangeMode == "fixed")
            scene.colorRange = core::ValueRange{view->range[0], view->range[1]};
        else if (difference->min <= difference->max)
            scene.colorRange = core::ValueRange{difference->min, difference->max};
    } else if (!view->colorVariable.empty()) {
        if (view->rangeMode == "fixed") {
            scene.colorRange = core::ValueRange{view->range[0], view->range[1]};
        } else if (view->rangeMode == "all") {
            // The range over every frame, so a series of figures shares one legend.
            double lo = 1e300, hi = -1e300;
            for (std::size_t k = 0; k < dataset->frameCount(); ++k)
                if (const auto* c = dataset->frame(k)->attribute(view->colorVariable)) {
                    lo = std::min(lo, c->min);
                    hi = std::max(hi, c->max);
                }
            if (lo <= hi)
                scene.colorRange = core::ValueRange{lo, hi};
        }
    }
    for (const auto& b : session.state().boxes)
        if (b.enabled)
            scene.boxes.push_back({glm::dvec3(b.min[0], b.min[1], b.min[2]),
                                   glm::dvec3(b.max[0], b.max[1], b.max[2]),
                                   b.mode == core::BoxMode::Keep ? glm::vec3(0.15f, 0.45f, 0.85f)
                                                                 : glm::vec3(0.85f, 0.25f, 0.2f)});
    // Visible fault surfaces, as the workbench shows them.
    std::optional<core::Fault> visibleSpheres; // the visible spheres' surface source, if shown
    for (const auto& st : session.state().surfaces) {
        const core::Fault* fault = session.state().fault(st.fault);
        if (st.visible && core::isVisibleSpheres(st.fault)) {
            visibleSpheres = core::visibleSpheresFault(*frame, visibility);
            fault = &*visibleSpheres;
        }
        if (!st.visible || !fault || !fault->visible)
            continue;
        if (std::none_of(fault->ids.begin(), fault->ids.end(), [&](std::int64_t id) { return frame->rowOf(id).has_value(); }))
            continue; // none of its members in this frame: nothing to draw
        try {
            scene.meshes.push_back(toMeshData(core::buildFaultSurface(*frame, {*fault, st}).mesh));
        } catch (const std::exception& e) {
            throw CommandError(std::string("render: surface of ") + e.what());
        }
        scene.meshes.back().opacity = static_cast<float>(st.opacity);
    }
    // The view's camera; one never placed (distance 0) keeps its angles and is fitted to the
    // model, as the viewport does.
    core::CameraState camera = view->camera;
    if (camera.distance <= 0) {
        const auto& lo = frame->centreMin();
        const auto& hi = frame->centreMax();
        const double w = request.width, h = request.height;
        const double legend = showsLegend(scene) ? std::min(0.4 * w, 115.0 * legendScale(request.width, request.height, 1.0f)) : 0.0;
        fitBesideLegend(camera, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, w, h, legend);
    }
    scene.camera = toRenderCamera(camera);

    RenderSettings settings;
    settings.width = request.width;
    settings.height = request.height;
    settings.transparent = request.transparent;
    try {
        const auto folder = std::filesystem::path(request.path).parent_path();
        if (!folder.empty())
            std::filesystem::create_directories(folder);
        renderSceneToPng(scene, settings, request.path);
    } catch (const std::exception& e) {
        throw CommandError(std::string("render: ") + e.what());
    }
}

void registerRenderOp(core::Session& session) {
    session.registerOp("render", [](core::Session& s, const Json& cmd) -> Json {
        core::args::onlyFields(cmd, {"view", "path", "size", "transparent", "frame"});
        FigureRequest request;
        request.view = core::args::optionalString(cmd, "view").value_or("main");
        request.path = s.outputPath(core::args::string(cmd, "path"));
        if (cmd.contains("size")) {
            const Json& size = cmd["size"];
            if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() ||
                !size[1].is_number_integer())
                throw CommandError("render: \"size\" must be [width, height] in pixels");
            request.width = size[0].get<int>();
            request.height = size[1].get<int>();
        }
        request.transparent = core::args::optionalBool(cmd, "transparent").value_or(false);
        if (auto f = core::args::optionalInteger(cmd, "frame")) {
            if (*f < 0)
                throw CommandError("render: \"frame\" must be >= 0");
            request.frame = static_cast<std::size_t>(*f);
        }
        renderSessionFigure(s, request);
        return nullptr;
    });
}

} // namespace faultline::ui
