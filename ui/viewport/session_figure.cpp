#include "ui/viewport/session_figure.hpp"

#include "core/color/colormap.hpp"
#include "core/model/frame_difference.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/color_range.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/view_colors.hpp"
#include "core/view/framing.hpp"
#include "ui/render/legend_layout.hpp"
#include "ui/render/offscreen.hpp"
#include "ui/render/surface_mesh.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <thread>

namespace faultline::ui {

using core::CommandError;
using core::Json;

RgbaImage renderSessionImage(core::Session& session, const FigureRequest& request,
                             std::shared_ptr<const core::Frame> loaded) {
    const core::ViewState* view = session.state().view(request.view);
    if (!view)
        throw CommandError("render: no view named \"" + request.view + "\"");
    auto dataset = session.dataset();
    if (!dataset)
        throw CommandError("render: no data is open");
    if (request.width < 16 || request.height < 16 || request.width > 16384 ||
        request.height > 16384)
        throw CommandError("render: size must lie between 16x16 and 16384x16384");
    const std::size_t frameIndex = request.frame ? *request.frame : session.frameOfView(*view);
    if (frameIndex >= dataset->frameCount())
        throw CommandError("render: frame " + std::to_string(frameIndex) + " out of range 0.." +
                           std::to_string(dataset->frameCount() - 1));
    const auto frame = loaded ? loaded : dataset->frame(frameIndex);

    SceneDescription scene;
    scene.frame = frame.get();
    const auto rowMask = session.faultRowMask(*frame);
    core::VisibilityResult visibility = core::computeVisibility(
        *frame, session.state().boxes, session.state().thresholds, rowMask.get());
    scene.visible = visibility.mask;
    scene.colorVariable = view->colorVariable;
    scene.style.contextPoints = view->contextPoints;
    scene.colorMap = view->colorMap;
    CategoryColoring categories; // "faults": each member in its fault's colour
    core::ViewColoring coloring;
    if (view->colorVariable == kFaultsVariable && !frame->attribute(kFaultsVariable)) {
        categories = faultColoring(*frame, session.state().faults);
        scene.colorColumn = categories.values.get();
        scene.colorMap = core::ColorMapSpec{core::ColorMapKind::Palette, 10, categories.palette};
        scene.colorRange = core::ValueRange{0.0, double(categories.palette.size())};
        scene.style.categories = legendEntries(categories); // the faults' names
    } else if (!view->colorVariable.empty() ||
               view->difference.mode != core::ColorDifference::Mode::None) {
        // The view's rule (core::colorView, as the workbench shows it), everything computed
        // here: the reference frame read, the range over every frame worked out.
        core::ViewColorSources sources;
        sources.frame = [&](std::size_t ref) { return dataset->frame(ref); };
        sources.difference = [](const std::shared_ptr<const core::Frame>& now,
                                const std::shared_ptr<const core::Frame>& ref,
                                core::ColorDifference::Mode mode, const std::string& variable) {
            try {
                return std::make_shared<const core::AttributeColumn>(
                    mode == core::ColorDifference::Mode::Change
                        ? core::variableChange(*now, *ref, variable)
                        : core::displacementSince(*now, *ref));
            } catch (const std::invalid_argument& e) { // a figure says why, not one colour
                throw CommandError(std::string("render: ") + e.what());
            }
        };
        // A movie's frames share its range (request.colorRange), worked out once for them all.
        sources.allFrames = [&](const core::ViewState& v, const std::string&,
                                core::ValueRange inFrame) {
            if (request.colorRange)
                return *request.colorRange;
            return core::colorRangeOverFrames(*dataset, v).value_or(inFrame);
        };
        sources.visibleRange = [](const core::Frame& f, const core::VisibilityResult& vis,
                                  const std::string& variable,
                                  bool percentiles) -> std::optional<core::ValueRange> {
            if (const auto r = percentiles
                                   ? core::maskedQuantiles(f, variable, vis.mask, 0.01, 0.99)
                                   : core::maskedRange(f, variable, vis.mask))
                return core::ValueRange{r->first, r->second};
            return std::nullopt;
        };
        coloring =
            core::colorView(*view, frameIndex, dataset->frameCount(), frame, &visibility, sources);
        scene.colorVariable = coloring.title;
        scene.colorColumn = coloring.column.get();
        // A variable without one value in this frame (incremental strain before its reference):
        // grey spheres and no legend, as the workbench's views show it (for the variable's own
        // column; a difference keeps its legend there too).
        if (!coloring.column)
            if (const core::AttributeColumn* own = frame->attribute(scene.colorVariable);
                own && own->hasNoValue())
                scene.style.showLegend = false;
        scene.colorRange = request.colorRange ? *request.colorRange : coloring.range;
    }
    for (const auto& b : session.state().boxes)
        if (b.enabled)
            scene.boxes.push_back({glm::dvec3(b.min[0], b.min[1], b.min[2]),
                                   glm::dvec3(b.max[0], b.max[1], b.max[2]),
                                   b.mode == core::BoxMode::Keep ? glm::vec3(0.15f, 0.45f, 0.85f)
                                                                 : glm::vec3(0.85f, 0.25f, 0.2f)});
    // Visible fault surfaces, as the workbench shows them.
    std::optional<core::Fault> visibleSpheres; // the visible spheres' surface source, if shown
    std::optional<core::Fault> formed;         // a fault as formed in this frame
    for (const auto& st : session.state().surfaces) {
        const core::Fault* fault = session.state().fault(st.fault);
        if (fault && st.visible) {
            formed = core::faultAsFormed(*frame, *fault, session.state().thresholds);
            fault = &*formed;
        }
        if (st.visible && core::isVisibleSpheres(st.fault)) {
            visibleSpheres = core::visibleSpheresFault(*frame, visibility);
            fault = &*visibleSpheres;
        }
        if (!st.visible || !fault || !fault->visible)
            continue;
        if (std::none_of(fault->ids.begin(), fault->ids.end(),
                         [&](std::int64_t id) { return frame->rowOf(id).has_value(); }))
            continue; // none of its members in this frame: nothing to draw
        try {
            // The session's surfaces of this frame: one surface.build made is drawn, not built
            // again (a movie builds each frame's once).
            const core::SurfaceReuse reuse = core::surfaceReuseFor(session, frameIndex);
            scene.meshes.push_back(
                toMeshData(core::buildFaultSurface(*frame, {*fault, st}, nullptr, reuse).mesh));
        } catch (const std::exception& e) {
            throw CommandError(std::string("render: surface of ") + e.what());
        }
        scene.meshes.back().opacity = static_cast<float>(st.opacity);
    }
    // The view's camera; one never placed (distance 0) keeps its angles and is fitted to the
    // model, as the viewport does.
    core::CameraState camera = request.camera ? *request.camera : view->camera;
    if (camera.distance <= 0) {
        const core::Framing framing = core::framingBounds(*frame); // far strays left out
        const double w = request.width, h = request.height;
        const double legend =
            showsLegend(scene) ? std::min(0.45 * w, legendPixels(scene, w, h)) : 0.0;
        fitBesideLegend(camera, framing.lo, framing.hi, w, h, legend);
    }
    scene.camera = toRenderCamera(camera);
    scene.style.caption = request.caption;

    RenderSettings settings;
    settings.width = request.width;
    settings.height = request.height;
    settings.transparent = request.transparent;
    try {
        return renderSceneToImage(scene, settings);
    } catch (const std::exception& e) {
        throw CommandError(std::string("render: ") + e.what());
    }
}

namespace {

void makeParentFolder(const std::string& path) {
    const auto folder = std::filesystem::path(path).parent_path();
    if (!folder.empty())
        std::filesystem::create_directories(folder);
}

} // namespace

void renderSessionFigure(core::Session& session, const FigureRequest& request) {
    const RgbaImage image = renderSessionImage(session, request);
    try {
        makeParentFolder(request.path);
        writePng(image, request.path);
    } catch (const std::exception& e) {
        throw CommandError(std::string("render: ") + e.what());
    }
}

bool isFrameSequencePattern(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    int conversions = 0;
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (name[i] != '%')
            continue;
        std::size_t j = i + 1;
        while (j < name.size() && std::isdigit(static_cast<unsigned char>(name[j])))
            ++j;
        if (j < name.size() && name[j] == 'd')
            ++conversions;
        i = j;
    }
    return conversions == 1;
}

std::string framePath(const std::string& pattern, std::size_t frame) {
    std::string out;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        std::size_t j = i + 1;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])))
            ++j;
        if (j < pattern.size() && pattern[j] == 'd') {
            const int width = std::min(12, std::atoi(pattern.substr(i + 1, j - i - 1).c_str()));
            std::string number = std::to_string(frame);
            if (int(number.size()) < width)
                number.insert(0, std::size_t(width) - number.size(), '0');
            out += number;
            i = j;
        } else {
            out += pattern[i];
        }
    }
    return out;
}

FrameSequence::FrameSequence(core::Session& session, SequenceRequest request)
    : m_session(session), m_request(std::move(request)) {
    FigureRequest& fig = m_request.figure;
    const core::ViewState* view = session.state().view(fig.view);
    if (!view)
        throw CommandError("render: no view named \"" + fig.view + "\"");
    auto dataset = session.dataset();
    if (!dataset)
        throw CommandError("render: no data is open");
    const std::size_t count = dataset->frameCount();
    if (m_request.first > m_request.last || m_request.last >= count)
        throw CommandError("render: \"frames\" [" + std::to_string(m_request.first) + ", " +
                           std::to_string(m_request.last) + "] must lie within 0.." +
                           std::to_string(count - 1) + ", first <= last");
    if (m_request.step < 1)
        throw CommandError("render: \"step\" must be at least 1");
    const bool movie = fig.path.size() > 4 && fig.path.substr(fig.path.size() - 4) == ".mp4";
    if (!movie && !isFrameSequencePattern(fig.path))
        throw CommandError("render: with \"frames\" the path must end in .mp4 (a movie) or "
                           "hold one frame number like %04d (a PNG sequence), got \"" +
                           fig.path + "\"");
    if (fig.width < 16 || fig.height < 16 || fig.width > 16384 || fig.height > 16384)
        throw CommandError("render: size must lie between 16x16 and 16384x16384");
    for (std::size_t f = m_request.first; f <= m_request.last; f += m_request.step)
        if (session.frameSelection().contains(f))
            m_frames.push_back(f);
    // One colour range for every frame: the view's fixed one, else the range over all frames
    // (what rangeMode "all" gives a single figure), so colours mean the same in every frame.
    // Every frame of the data, not only the movie's: a movie of frames 0-30 then colours as the
    // view, a figure and a movie of the whole run do (issue 41), and shards as the whole run.
    if (!fig.colorRange && view->rangeMode != core::RangeMode::Fixed)
        fig.colorRange = core::colorRangeOverFrames(*dataset, *view);
    // One camera: the view's, or fitted to the first and last frames of the range together.
    if (!fig.camera && view->camera.distance <= 0) {
        core::CameraState camera = view->camera;
        // Far strays left out of each (core/view/framing).
        const core::Framing a = core::framingBounds(*dataset->frame(m_request.first));
        const core::Framing b = core::framingBounds(*dataset->frame(m_request.last));
        std::array<double, 3> lo, hi;
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(a.lo[k], b.lo[k]), hi[k] = std::max(a.hi[k], b.hi[k]);
        const double w = fig.width, h = fig.height;
        const bool legend = !view->colorVariable.empty() && view->colorVariable != kFaultsVariable;
        const double strip =
            legend ? std::min(0.4 * w, 115.0 * legendScale(fig.width, fig.height, 1.0f)) : 0.0;
        fitBesideLegend(camera, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, w, h, strip);
        fig.camera = camera;
    }
    try {
        if (movie) {
            makeParentFolder(fig.path);
            MovieSettings settings;
            settings.width = fig.width;
            settings.height = fig.height;
            settings.framesPerSecond = m_request.framesPerSecond;
            m_movie = std::make_unique<MovieWriter>(fig.path, settings);
        }
    } catch (const std::exception& e) {
        throw CommandError(std::string("render: ") + e.what());
    }
    core::PrefetchSettings prefetch;
    prefetch.lookAhead = 3;
    m_prefetcher = std::make_unique<core::FramePrefetcher>(dataset, prefetch);
    if (!m_frames.empty())
        m_prefetcher->request(m_frames.front());
}

FrameSequence::~FrameSequence() = default;

bool FrameSequence::step(bool wait) {
    if (m_next >= m_frames.size()) {
        finish();
        return false;
    }
    const std::size_t f = m_frames[m_next];
    core::FrameRequestResult r = m_prefetcher->request(f);
    while (r.status == core::FrameStatus::Loading) {
        if (!wait)
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        r = m_prefetcher->request(f);
    }
    if (r.status == core::FrameStatus::Failed)
        throw CommandError("render: frame " + std::to_string(f) + ": " + r.error);
    FigureRequest fig = m_request.figure;
    fig.frame = f;
    if (m_movie)
        fig.caption =
            "frame " + std::to_string(f) + "   timestep " + std::to_string(r.frame->timestep);
    else
        fig.path = framePath(fig.path, f);
    RgbaImage image = renderSessionImage(m_session, fig, r.frame);
    // Ask for the one after next now: the prefetcher loads it while this one is written.
    if (m_next + 1 < m_frames.size())
        m_prefetcher->request(m_frames[m_next + 1]);
    try {
        if (m_movie) {
            m_movie->add(image);
        } else {
            makeParentFolder(fig.path);
            writePng(image, fig.path);
        }
    } catch (const std::exception& e) {
        throw CommandError(std::string("render: ") + e.what());
    }
    ++m_next;
    if (m_next == m_frames.size())
        finish();
    return m_next < m_frames.size();
}

void FrameSequence::finish() {
    while (m_next < m_frames.size())
        step(true);
    if (m_finished)
        return;
    m_finished = true;
    if (m_movie) {
        try {
            m_movie->finish();
        } catch (const std::exception& e) {
            throw CommandError(std::string("render: ") + e.what());
        }
    }
}

void registerRenderOp(core::Session& session) {
    session.registerOp("render", [](core::Session& s, const Json& cmd) -> Json {
        core::args::onlyFields(
            cmd, {"view", "path", "size", "transparent", "frame", "frames", "step", "fps"});
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
        if (!cmd.contains("frames")) {
            for (const char* field : {"step", "fps"})
                if (cmd.contains(field))
                    throw CommandError(std::string("render: \"") + field +
                                       "\" needs \"frames\": [first, last]");
            renderSessionFigure(s, request);
            return nullptr;
        }
        const Json& frames = cmd["frames"];
        if (!frames.is_array() || frames.size() != 2 || !frames[0].is_number_integer() ||
            !frames[1].is_number_integer() || frames[0].get<long long>() < 0 ||
            frames[1].get<long long>() < 0)
            throw CommandError("render: \"frames\" must be [first, last], frame numbers from 0");
        if (request.frame)
            throw CommandError("render: give \"frame\" or \"frames\", not both");
        SequenceRequest sequence;
        sequence.figure = request;
        sequence.first = frames[0].get<std::size_t>();
        sequence.last = frames[1].get<std::size_t>();
        const auto step = core::args::optionalInteger(cmd, "step").value_or(1);
        const auto fps = core::args::optionalInteger(cmd, "fps").value_or(10);
        if (step < 1)
            throw CommandError("render: \"step\" must be at least 1");
        if (fps < 1 || fps > 120)
            throw CommandError("render: \"fps\" must lie between 1 and 120");
        sequence.step = static_cast<std::size_t>(step);
        sequence.framesPerSecond = static_cast<int>(fps);
        FrameSequence(s, sequence).finish();
        return nullptr;
    });
}

} // namespace faultline::ui
