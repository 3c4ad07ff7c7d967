// ViewRenderer: what a viewport asks of the 3-D renderer. The workbench describes each view's
// scene after the UI is built; the renderer draws it into a texture the viewport panel shows.
// The GUI installs an OpenGL one; headless runs have none and the viewport says so.
#pragma once

#include "core/model/frame.hpp"
#include "core/selection/cutting_box.hpp"
#include "core/session/session_state.hpp"
#include "ui/render/renderer.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

// A fault's surface as a view draws it (opacity from the session's settings).
struct ViewSurface {
    std::string fault;
    std::shared_ptr<const MeshData> mesh;
    float opacity = 1.0f;
};

struct ViewScene {
    std::string view;                                   // the view's name
    std::shared_ptr<const core::Frame> frame;           // null: no data
    const std::vector<std::uint8_t>* visible = nullptr; // a byte per row; null: all
    std::uint64_t visibleKey = 0;                       // changes when the mask changes
    std::string colorVariable; // empty: one colour; else the legend's title
    // Values to colour by instead of the frame's colorVariable column (difference colouring).
    std::shared_ptr<const core::AttributeColumn> colorColumn;
    core::ColorMapSpec colorMap;            // the view's; categories use palette below
    std::array<double, 2> colorRange{0, 1}; // resolved
    core::CameraState camera;               // resolved (fitted, previewed)
    std::vector<core::CuttingBox> boxes;    // enabled boxes to outline
    std::optional<std::size_t> selectedBox; // index into boxes: draw face handles
    std::optional<int> activeFace;          // 0..5 (-x +x -y +y -z +z), highlighted
    std::vector<ViewSurface> surfaces;      // fault surfaces, drawn with the spheres
    bool contextPoints = false;             // hidden spheres as faint small points
    bool valueLegend = true; // false: the colour variable has no value here (no legend)
    // Categories: colour value k + 0.5 takes palette[k] (colorRange is [0, size]); their legend
    // names each colour (faults; empty: no legend).
    std::vector<glm::vec3> palette;
    std::vector<LegendEntry> legend;
    int width = 0, height = 0; // pixels
};

class ViewRenderer {
  public:
    virtual ~ViewRenderer() = default;
    // Draws the scene into the view's texture (made or resized as needed).
    virtual void render(const ViewScene& scene) = 0;
    // The texture holding the view's last render (an OpenGL name), 0 when there is none yet.
    virtual unsigned int texture(const std::string& view) const = 0;
    // A view was removed: free its texture.
    virtual void forget(const std::string& view) = 0;
    // One line for the status bar / About box, e.g. the GL renderer's name.
    virtual std::string description() const = 0;
    // Whether box outlines and face handles are part of the image (else the viewport draws them).
    virtual bool drawsBoxes() const { return false; }
};

} // namespace faultline::ui
