// One view of the Viewports panel: its header (frame binding, colour, camera link, selection
// tool) and its image with mouse interaction (orbit, pan, zoom, dragging the selected box's
// faces, picking spheres for faults) and the overlays drawn over the renderer's image (box
// outlines, handles, axes, frame label, the selection outline and the selected fault's members).
#pragma once

#include "core/session/commands.hpp"
#include "ui/context/panel_context.hpp"
#include "ui/panels/viewport_selection.hpp"

#include <imgui.h>

#include <optional>
#include <string>

namespace faultline::ui {

class ViewportCells {
  public:
    void draw(PanelContext& wb, const core::ViewState& view, ImVec2 pos, ImVec2 size);
    // Camera commands for every view at once (one undo step): linked views follow the main one.
    void presetAll(PanelContext& wb, const char* preset);
    void fitAll(PanelContext& wb);
    void fitVisible(PanelContext& wb); // to the visible spheres (boxes, thresholds, faults applied)
    // Sets a camera.set's target and distance to fit the view's visible spheres, seen with
    // `orientation`'s azimuth and elevation (the view's own when null).
    void fitVisibleInto(PanelContext& wb, const std::string& view, core::cmd::CameraSet& cmd,
                        const core::CameraState* orientation);
    // Orbit / Rectangle / Lasso: what a left drag does in every view (the tool is the workbench's).
    void drawToolButtons(PanelContext& wb);
    void setOrthographic(PanelContext& wb, bool ortho);

  private:
    void drawHeader(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d, ImVec2 pos,
                    float width);
    static constexpr float kTwoRowHeader = 300.0f; // logical pixels
    static float headerHeight(PanelContext& wb, float width);
    void drawColourPopup(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d);
    void drawDifference(PanelContext& wb, const core::ViewState& view);
    void drawFramePopup(PanelContext& wb, const core::ViewState& view);

    void interact(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d, ImVec2 pos,
                  ImVec2 size);
    void drawOverlays(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d,
                      const core::CameraState& cam, ImVec2 pos, ImVec2 size);
    void emitForViews(PanelContext& wb,
                      const std::function<void(const std::string&, core::cmd::CameraSet&)>& fill);

    enum class DragMode { None, Orbit, Pan, BoxFace, Select };
    struct Drag {
        DragMode mode = DragMode::None;
        std::string view;
        core::CameraState start;
        ImVec2 startMouse;
        int face = -1;
        std::array<double, 3> boxMin{}, boxMax{};
        core::CameraState current;
    };
    Drag m_drag;
    ViewportSelection m_selection;
    struct Wheel {
        std::string view;
        core::CameraState camera;
        double lastTime = 0;
    };
    std::optional<Wheel> m_wheel;
    core::Json m_pendingBox;
    int m_hoverFace = -1;
    std::string m_hoverView;
    int m_frameEdit = 0;
    bool m_frameRelative = true;
    double m_rangeEdit[2] = {0, 1};
    double m_rangeShown[2] = {0, 1}; // the view's range the fields last took
    bool m_sinceRelative = false;
    int m_sinceEdit = 0;
};

} // namespace faultline::ui
