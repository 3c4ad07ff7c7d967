// Viewports panel: the session's views side by side (up to four), each with its own frame
// binding (the current frame plus an offset, or a fixed frame) and colour variable, cameras
// linked or independent. Camera drags and box-handle drags preview live and emit one command
// when released; the 3-D image comes from the ViewRenderer (viewport_interaction.cpp).
#include "core/session/commands.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/panels/viewport_cell.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <algorithm>

namespace faultline::ui {

namespace {

std::string uniqueViewName(const core::SessionState& s) {
    for (int k = 2;; ++k) {
        std::string n = "view " + std::to_string(k);
        if (!s.view(n))
            return n;
    }
}

class ViewportsPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kViewports; }
    const char* title() const override { return "Viewports"; }
    bool padded() const override { return false; }

    void draw(PanelContext& wb) override {
        const core::SessionState& s = wb.state();
        const float scale = wb.scale();
        // Toolbar.
        ImGui::SetCursorPos(ImVec2(6 * scale, 4 * scale));
        ImGui::BeginDisabled(s.views.size() >= 4);
        if (ImGui::Button("Add view")) {
            const std::string added = uniqueViewName(s);
            const long long count =
                wb.dataset() ? static_cast<long long>(wb.dataset()->frameCount()) : 1;
            // Compared with an earlier moment.
            wb.emit(core::cmd::ViewAdd(added).offset(-std::min<long long>(10, count - 1)));
            // The cells narrow: every view is fitted again, the new one too (walkthrough of
            // issue 41: with two views each legend covered the block's east end until Fit).
            // Camera moves are no undo steps, so undo still takes the view away.
            for (const auto& v : s.views)
                wb.emit(core::cmd::CameraSet(v.name).distance(0.0));
            wb.emit(core::cmd::CameraSet(added).distance(0.0));
        }
        wb.mark("viewports.add");
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("Another view side by side (up to four), e.g. ten frames earlier");
        // The toolbar flows onto a second row where the panel is narrow.
        for (const char* preset : {"top", "front", "side", "iso"}) {
            char label[16];
            std::snprintf(label, sizeof label, "%c%s", preset[0] - 32, preset + 1);
            flowSameLine(buttonWidth(label));
            if (ImGui::Button(label))
                m_cells.presetAll(wb, preset);
            wb.mark(std::string("viewports.preset.") + preset);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "%s", std::string(preset) == "top"
                              ? "Map view: from above, north up (fitted to the visible spheres)"
                          : std::string(preset) == "front" ? "From the south, looking north"
                          : std::string(preset) == "side"  ? "From the east, looking west"
                                                           : "Oblique, from the south-south-west");
        }
        flowSameLine(buttonWidth("Fit"));
        if (ImGui::Button("Fit"))
            m_cells.fitAll(wb);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Fit the model in the views (F)");
        flowSameLine(buttonWidth("Fit visible"));
        if (ImGui::Button("Fit visible"))
            m_cells.fitVisible(wb);
        wb.mark("viewports.fit_visible");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Fit the visible spheres in the views (boxes, thresholds and faults applied)");
        const core::ViewState* main = s.view("main");
        bool context = main && main->contextPoints;
        flowSameLine(checkboxWidth("Hidden as points"));
        if (ImGui::Checkbox("Hidden as points", &context)) {
            std::vector<core::Json> batch;
            for (const auto& v : s.views)
                batch.push_back(core::cmd::ViewSet(v.name).contextPoints(context));
            wb.emit(core::cmd::batch(std::move(batch)));
        }
        wb.mark("viewports.context");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Draw the hidden spheres as faint small points, for context");
        flowSameLine(checkboxWidth("Orthographic"));
        bool ortho = main && main->camera.orthographic;
        if (ImGui::Checkbox("Orthographic", &ortho))
            m_cells.setOrthographic(wb, ortho);
        flowSameLine(buttonWidth("Orbit") + buttonWidth("Rectangle") + buttonWidth("Lasso") + 2);
        m_cells.drawToolButtons(wb);

        // Cells: one to three side by side, four as two by two.
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        const ImVec2 avail = ImGui::GetContentRegionAvail();
        const std::size_t n = std::max<std::size_t>(1, s.views.size());
        const int cols = n <= 3 ? static_cast<int>(n) : 2;
        const int rows = n <= 3 ? 1 : 2;
        const float gap = std::round(3 * scale);
        const float cw = (avail.x - gap * static_cast<float>(cols - 1)) / static_cast<float>(cols);
        const float ch = (avail.y - gap * static_cast<float>(rows - 1)) / static_cast<float>(rows);
        for (std::size_t k = 0; k < s.views.size(); ++k) {
            const int c = static_cast<int>(k) % cols, r = static_cast<int>(k) / cols;
            const ImVec2 a(origin.x + static_cast<float>(c) * (cw + gap),
                           origin.y + static_cast<float>(r) * (ch + gap));
            m_cells.draw(wb, s.views[k], a, ImVec2(cw, ch));
        }
    }

  private:
    ViewportCells m_cells;
};

} // namespace

std::unique_ptr<Panel> makeViewportsPanel() { return std::make_unique<ViewportsPanel>(); }

} // namespace faultline::ui
