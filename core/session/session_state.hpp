// SessionState: everything a user sees and can save: data sources, frame, views, boxes,
// thresholds, faults, surface settings, dock layout. Plain data; changed only by commands.
#pragma once

#include "core/color/colormap.hpp"

#include "core/faults/fault.hpp"
#include "core/motion/strain_spec.hpp"
#include "core/selection/cutting_box.hpp"
#include "core/selection/variable_threshold.hpp"
#include "core/surface/surface_params.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

inline constexpr int kSessionSchema = 1;

// An orbit camera as saved: the renderer derives its matrices from these.
struct CameraState {
    std::array<double, 3> target{0, 0, 0};
    double distance = 0;   // 0: not set yet, fit the model when first shown
    double azimuth = 0;    // degrees, clockwise from north (+y) as seen from above
    double elevation = 20; // degrees above horizontal
    double fovY = 35;      // degrees; ignored when orthographic
    bool orthographic = false;
    bool operator==(const CameraState&) const = default;
};

// Which frame a view shows: the session's current frame plus an offset, or a fixed frame.
struct FrameBinding {
    bool relative = true;
    long long value = 0; // offset when relative, frame index when absolute
    bool operator==(const FrameBinding&) const = default;
};

// Difference colouring: a view coloured by how its variable changed, or how far each sphere
// moved, since a reference frame (absolute, or an offset from the frame the view shows).
struct ColorDifference {
    enum class Mode { None, Change, Displacement };
    Mode mode = Mode::None;
    FrameBinding reference{false, 0};
    bool operator==(const ColorDifference&) const = default;
};
std::string_view differenceModeName(ColorDifference::Mode mode); // none | change | displacement
std::optional<ColorDifference::Mode> parseDifferenceMode(std::string_view name);

struct ViewState;
ViewState mainView();

struct ViewState {
    std::string name;
    FrameBinding frame;
    std::string colorVariable;                     // empty: a plain colour
    ColorMapSpec colorMap{ColorMapKind::BlueRed};  // a journal name ("blue-red") only in JSON
    RangeMode rangeMode = RangeMode::CurrentFrame; // "frame" | "all" | "fixed" | "percentile"
    std::array<double, 2> range{0, 1};             // used when rangeMode is Fixed
    ColorDifference difference;
    CameraState camera;
    bool linkedCamera = true;
    bool contextPoints = false; // hidden spheres drawn as faint small points (context mode)
    bool operator==(const ViewState&) const = default;
};

// The reference frame of a view's difference colouring when it shows `shown` of `count` frames.
std::size_t referenceFrame(const ViewState& view, std::size_t shown, std::size_t count);
// The range a view's colours take: its mode, except that a change or a displacement spans all
// frames unless fixed (issue 41: a colour then means the same at every frame), whatever the
// mode says. The live view, figures and the colour popup all read it from here.
RangeMode effectiveRangeMode(const ViewState& view);
// What a view's colours mean, for its legend: "strain", "strain change since frame 10",
// "displacement since frame 0" (empty: one colour).
std::string colorTitle(const ViewState& view, std::size_t referenceFrame);

inline ViewState mainView() {
    ViewState v;
    v.name = "main";
    return v;
}

// Which spheres faults let through, before boxes and thresholds.
struct FaultFilter {
    enum class Mode { All, Labelled, Only };
    Mode mode = Mode::All; // All: everything except members of hidden faults
    std::string fault;     // for Only
    bool operator==(const FaultFilter&) const = default;
};
std::string_view faultFilterModeName(FaultFilter::Mode mode); // all | labelled | only
std::optional<FaultFilter::Mode> parseFaultFilterMode(std::string_view name);
// "all, labelled or only", for messages.
std::string faultFilterModeNames();

// The surface source that is not a fault: the spheres visible in the frame (thresholds, boxes,
// fault filter), as the views show them. Surface settings and journals name it like a fault:
// {"op":"surface.build","fault":"*visible",...}; no fault may take this name.
inline constexpr std::string_view kVisibleSpheres = "*visible";
inline bool isVisibleSpheres(std::string_view name) { return name == kVisibleSpheres; }

struct SurfaceSettings {
    std::string fault;                                     // a fault's name, or kVisibleSpheres
    MetaballKernel kernel = MetaballKernel::InverseSquare; // "inverse-square" etc. only in JSON
    double voxel = 0;                                      // 0: radius / 3
    double iso = 1.0;
    bool visible = true;
    double opacity = 0.8;
    // Figure 4 colour: a voxel takes the colour of each sphere whose radius + colorReach holds
    // it (averaged), else the initial colour. The spheres take the fault's colour or, with
    // colorBy, a colour map of that variable over colorRange (none: its range in the frame).
    std::string colorBy;                          // "": the fault's colour
    ColorMapSpec colorMap{ColorMapKind::Viridis}; // a journal name only in JSON
    std::optional<std::array<double, 2>> colorRange;
    std::optional<double> colorReach; // none: with colorBy twice the spheres' mean radius (a
                                      // surface at a wrapping iso lies up to 3 radii out where it
                                      // is concave), else 0 (one colour needs no reach)
    // Without colorBy, the surface's one colour (issue 41: a surface in its fault's colour is
    // hard to see among that fault's spheres); none: the fault's.
    std::optional<std::array<double, 3>> color;
    std::optional<std::array<double, 3>> initialColor; // none: the fault's; white with colorBy
                                                       // (no sphere in reach, not a low value)
    bool operator==(const SurfaceSettings&) const = default;
};

// As JSON: core/session/items/surface_codec.hpp.

struct SessionState {
    std::vector<std::string> dataPaths; // absolute in memory; saved relative to the session file
    std::size_t frame = 0;
    std::vector<ViewState> views{mainView()};
    std::vector<CuttingBox> boxes;
    std::vector<VariableThreshold> thresholds;
    std::vector<Fault> faults;
    FaultFilter faultFilter;
    std::vector<SurfaceSettings> surfaces;
    std::vector<StrainSpec> strains; // variables derived from motion (strain.add), in order
    nlohmann::json dockLayout = nlohmann::json::object(); // owned by the UI; kept as it is

    ViewState* view(std::string_view name);
    const ViewState* view(std::string_view name) const;
    CuttingBox* box(std::string_view name);
    const CuttingBox* box(std::string_view name) const;
    VariableThreshold* threshold(std::string_view variable);
    const VariableThreshold* threshold(std::string_view variable) const;
    Fault* fault(std::string_view name);
    const Fault* fault(std::string_view name) const;
    // A fault, or kVisibleSpheres: what a surface can be built from.
    bool hasSurfaceSource(std::string_view name) const {
        return fault(name) || isVisibleSpheres(name);
    }
    SurfaceSettings* surface(std::string_view fault);
    const SurfaceSettings* surface(std::string_view fault) const;
    // The surfaces ticked to show whose fault (or the visible spheres) exists, in table order:
    // what "export the shown surfaces" writes.
    std::vector<std::string> shownSurfaces() const;
    bool operator==(const SessionState&) const = default;
};

} // namespace faultline::core
