// ViewportSelection: building faults by picking spheres in a view. A click with Ctrl (or with a
// selection tool on) toggles the sphere under the cursor in the selected fault; with the
// Rectangle or Lasso tool a left drag outlines the visible spheres whose centres fall inside:
// added to the selected fault (a new fault when none is selected), Ctrl removes them, Shift
// makes a new fault. Each gesture is one journal command (fault.create/add/remove with ids).
#pragma once

#include "core/view/sphere_picker.hpp"
#include "ui/context/panel_context.hpp"
#include "ui/viewport/fault_edit.hpp"

#include <imgui.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace faultline::ui {

// The radius in pixels of the dot that marks a fault member: under half the sphere on screen
// (pixelsPerWorld at the camera's distance), at least 1 px and at most 3 px times the UI scale,
// so a whole-model view shows dots, not a black carpet of rings.
float memberMarkerRadius(float sphereRadius, float pixelsPerWorld, float uiScale);

class ViewportSelection {
  public:
    // The left button went down in `view`: true when the selection takes this gesture (a
    // selection tool is on, or Ctrl is held).
    bool press(PanelContext& wb, const std::string& view, ImVec2 mouse);
    void drag(ImVec2 mouse, float scale); // while the button is held
    // The button came up: emits the gesture's command. pos/size: the view's image on screen.
    void release(PanelContext& wb, const ViewDisplay& d, ImVec2 mouse, ImVec2 pos, ImVec2 size);
    bool active() const { return m_active; }
    const std::string& view() const { return m_view; }
    // A Ctrl+press without a tool that became a drag: the caller orbits instead, as before.
    bool becameOrbit() const { return m_active && m_tool == ViewportTool::Orbit && !isClick(); }
    void cancel() { m_active = false, m_points.clear(); }

    // The rectangle or lasso being drawn.
    void drawOutline(ImDrawList* dl, float scale) const;
    // The selected fault's visible members as dots (while a tool is on or Ctrl is held).
    void drawMembers(PanelContext& wb, const ViewDisplay& d, const core::CameraState& cam,
                     ImVec2 pos, ImVec2 size) const;

  private:
    bool isClick() const; // the mouse barely moved: pick one sphere
    std::vector<std::int64_t> idsInShape(const ViewDisplay& d, ImVec2 pos, ImVec2 size,
                                         bool throughDepth) const;
    std::vector<std::int64_t> idUnder(const ViewDisplay& d, ImVec2 mouse, ImVec2 pos, ImVec2 size);

    // The selected fault's visible member rows, kept while the session, frame and visibility
    // stay the same: looking a million ids up every UI frame took tens of milliseconds.
    struct MemberRows {
        std::uint64_t version = ~std::uint64_t{0};
        std::shared_ptr<const void> frame, visibility; // held: no address reuse can fool the key
        std::string fault;
        std::vector<std::uint32_t> rows;
    };
    mutable MemberRows m_members;

    bool m_active = false;
    std::string m_view;
    ViewportTool m_tool = ViewportTool::Orbit;
    FaultEditOp m_op = FaultEditOp::Add;
    std::vector<ImVec2> m_points; // screen pixels: rectangle corners, or the lasso's path
    float m_clickSlop = 4;

    core::SpherePicker m_picker; // over the visible spheres of the frame last picked in
    std::shared_ptr<const core::Frame> m_pickFrame;
    std::shared_ptr<const core::VisibilityResult> m_pickVisibility;
};

} // namespace faultline::ui
