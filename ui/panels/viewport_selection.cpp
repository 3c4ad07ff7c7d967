#include "ui/panels/viewport_selection.hpp"

#include "core/view/camera.hpp"
#include "core/view/screen_selection.hpp"
#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <algorithm>
#include <cmath>

namespace faultline::ui {

namespace {

core::ScreenMapping mappingOf(const ViewDisplay& d, const core::CameraState& cam, ImVec2 size) {
    const double aspect = size.x / std::max(1.0f, size.y);
    const double radius = d.frame ? d.sceneRadius : 1.0;
    return {projectionMatrix(cam, aspect, radius) * viewMatrix(cam), glm::dvec2(size.x, size.y)};
}

} // namespace

bool ViewportSelection::press(PanelContext& wb, const std::string& view, ImVec2 mouse) {
    const ImGuiIO& io = ImGui::GetIO();
    m_tool = wb.selection().tool;
    if (m_tool == ViewportTool::Orbit && !io.KeyCtrl)
        return false;
    m_active = true;
    m_view = view;
    m_points = {mouse, mouse};
    m_clickSlop = 4 * wb.scale();
    m_op = io.KeyCtrl && m_tool != ViewportTool::Orbit ? FaultEditOp::Remove
           : io.KeyShift                               ? FaultEditOp::NewFault
                                                       : FaultEditOp::Add;
    return true;
}

void ViewportSelection::drag(ImVec2 mouse, float scale) {
    if (!m_active)
        return;
    if (m_tool == ViewportTool::Lasso) {
        const ImVec2 last = m_points.back();
        if (std::hypot(mouse.x - last.x, mouse.y - last.y) >= 2.0f * scale)
            m_points.push_back(mouse);
    } else {
        m_points.back() = mouse;
    }
}

bool ViewportSelection::isClick() const {
    for (const ImVec2& p : m_points)
        if (std::hypot(p.x - m_points.front().x, p.y - m_points.front().y) > m_clickSlop)
            return false;
    return true;
}

void ViewportSelection::release(PanelContext& wb, const ViewDisplay& d, ImVec2 mouse, ImVec2 pos,
                                ImVec2 size) {
    if (!m_active)
        return;
    drag(mouse, wb.scale());
    m_active = false;
    if (!d.frame || !d.visibility)
        return;
    const bool click = isClick();
    std::vector<std::int64_t> ids = click ? idUnder(d, m_points.front(), pos, size)
                                          : idsInShape(d, pos, size, wb.selection().throughDepth);
    const FaultEdit edit = faultEdit(wb.state(), wb.selection().faults, std::move(ids),
                                     click ? FaultEditOp::Toggle : m_op);
    if (!edit.command.is_null()) {
        const std::string next = edit.selectNext;
        wb.emit(edit.command, [&wb, next] {
            if (!next.empty())
                wb.selection().faults = {next};
        });
    }
    wb.info(edit.message);
    m_points.clear();
}

std::vector<std::int64_t> ViewportSelection::idsInShape(const ViewDisplay& d, ImVec2 pos,
                                                        ImVec2 size, bool throughDepth) const {
    const core::Frame& f = *d.frame;
    const core::ScreenMapping mapping = mappingOf(d, d.camera, size);
    std::vector<std::uint32_t> rows;
    if (m_tool == ViewportTool::Rectangle) {
        const glm::dvec2 a(m_points.front().x - pos.x, m_points.front().y - pos.y);
        const glm::dvec2 b(m_points.back().x - pos.x, m_points.back().y - pos.y);
        rows = core::rowsInRectangle(mapping, f.x, f.y, f.z, d.visibility->mask, a, b);
    } else {
        std::vector<glm::dvec2> polygon;
        polygon.reserve(m_points.size());
        for (const ImVec2& p : m_points)
            polygon.emplace_back(p.x - pos.x, p.y - pos.y);
        rows = core::rowsInPolygon(mapping, f.x, f.y, f.z, d.visibility->mask, polygon);
    }
    // Issue 41: a rectangle in Front view took 1,030 spheres through the whole depth; by default
    // only those the user can see.
    if (!throughDepth)
        rows = core::frontmostRows(mapping, f.x, f.y, f.z, f.radius, d.visibility->mask, rows);
    std::vector<std::int64_t> ids;
    ids.reserve(rows.size());
    for (std::uint32_t r : rows)
        ids.push_back(f.ids[r]);
    return ids;
}

std::vector<std::int64_t> ViewportSelection::idUnder(const ViewDisplay& d, ImVec2 mouse, ImVec2 pos,
                                                     ImVec2 size) {
    if (m_pickFrame != d.frame || m_pickVisibility != d.visibility) {
        const core::Frame& f = *d.frame;
        m_picker.build(f.x, f.y, f.z, f.radius, d.visibility->mask);
        m_pickFrame = d.frame;
        m_pickVisibility = d.visibility;
    }
    const double aspect = size.x / std::max(1.0f, size.y);
    const glm::dvec2 ndc((mouse.x - pos.x) / size.x * 2.0 - 1.0,
                         1.0 - (mouse.y - pos.y) / size.y * 2.0);
    const auto hit = m_picker.pick(core::cameraRay(toRenderCamera(d.camera), ndc, aspect));
    if (!hit)
        return {};
    return {d.frame->ids[hit->row]};
}

void ViewportSelection::drawOutline(ImDrawList* dl, float scale) const {
    if (!m_active || m_points.size() < 2 || isClick())
        return;
    const ImU32 line = IM_COL32(255, 140, 20, 255), fill = IM_COL32(255, 140, 20, 40);
    if (m_tool == ViewportTool::Rectangle) {
        const ImVec2 a = m_points.front(), b = m_points.back();
        const ImVec2 lo(std::min(a.x, b.x), std::min(a.y, b.y)),
            hi(std::max(a.x, b.x), std::max(a.y, b.y));
        dl->AddRectFilled(lo, hi, fill);
        dl->AddRect(lo, hi, line, 0, 0, 1.5f * scale);
    } else if (m_tool == ViewportTool::Lasso) {
        dl->AddPolyline(m_points.data(), static_cast<int>(m_points.size()), line, 0, 1.5f * scale);
        dl->AddLine(m_points.back(), m_points.front(), IM_COL32(255, 140, 20, 130),
                    1.0f * scale); // closes it
    }
}

float memberMarkerRadius(float sphereRadius, float pixelsPerWorld, float uiScale) {
    const float r = 0.45f * sphereRadius * pixelsPerWorld;
    return std::clamp(std::isfinite(r) ? r : 1.0f, 1.0f, 3.0f * uiScale);
}

void ViewportSelection::drawMembers(PanelContext& wb, const ViewDisplay& d,
                                    const core::CameraState& cam, ImVec2 pos, ImVec2 size) const {
    if (!d.frame || !d.visibility || wb.selection().faults.size() != 1)
        return;
    if (wb.selection().tool == ViewportTool::Orbit && !ImGui::GetIO().KeyCtrl)
        return;
    const core::Fault* f = wb.state().fault(*wb.selection().faults.begin());
    if (!f)
        return;
    const core::ScreenMapping mapping = mappingOf(d, cam, size);
    const ImU32 colour =
        ImGui::ColorConvertFloat4ToU32(ImVec4(f->color[0], f->color[1], f->color[2], 1.0f));
    const ImU32 ring = IM_COL32(20, 20, 20, 220);
    const double viewHeight = 2.0 * cam.distance * std::tan(0.5 * cam.fovY * M_PI / 180.0);
    const float pixelsPerWorld = viewHeight > 0.0 ? static_cast<float>(size.y / viewHeight) : 1.0f;
    MemberRows& m = m_members;
    const std::uint64_t version = wb.sessionVersion();
    if (m.version != version || m.frame != d.frame || m.visibility != d.visibility ||
        m.fault != f->name) {
        m.version = version, m.frame = d.frame, m.visibility = d.visibility;
        m.fault = f->name;
        m.rows.clear();
        for (std::int64_t id : f->ids)
            if (const auto row = d.frame->rowOf(id); row && d.visibility->mask[*row])
                m.rows.push_back(static_cast<std::uint32_t>(*row));
    }
    std::size_t drawn = 0;
    glm::dvec2 p;
    for (const std::uint32_t row : m.rows) {
        if (!core::projectToScreen(mapping, d.frame->x[row], d.frame->y[row], d.frame->z[row], p))
            continue;
        const ImVec2 c(pos.x + static_cast<float>(p.x), pos.y + static_cast<float>(p.y));
        // Dots as large as the spheres allow; a dark ring only where there is room for it.
        const float r = memberMarkerRadius(d.frame->radius[row], pixelsPerWorld, wb.scale());
        if (r >= 2.0f * wb.scale())
            ImGui::GetWindowDrawList()->AddCircleFilled(c, r + 1.0f, ring, 8);
        ImGui::GetWindowDrawList()->AddCircleFilled(c, r, colour, 8);
        if (++drawn >= 50000)
            break;
    }
}

} // namespace faultline::ui
