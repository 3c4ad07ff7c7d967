// Cutting boxes panel: the list (enable, name, keep/cut), add/duplicate/delete, and an editor
// for the selected box: name, mode, min/max per axis as numbers and as fractions of the model.
#include "core/session/commands.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/number_field.hpp"
#include "ui/widgets/range_slider.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include "core/session/session_json.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace faultline::ui {

namespace {

std::string uniqueName(const core::SessionState& s, const std::string& stem) {
    for (int k = 1;; ++k) {
        std::string name = stem + " " + std::to_string(k);
        if (!s.box(name))
            return name;
    }
}

class BoxesPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kBoxes; }
    const char* title() const override { return "Cutting boxes"; }

    void draw(PanelContext& wb) override {
        const core::SessionState& s = wb.state();
        const ViewDisplay* main = wb.mainDisplay();
        const core::Frame* frame = main && main->frame ? main->frame.get() : nullptr;
        const ModelBounds model = frame ? main->bounds : ModelBounds{};

        ImGui::BeginDisabled(!frame);
        if (ImGui::Button("Add")) {
            const std::string name = uniqueName(s, "box");
            wb.emit(core::cmd::boxAdd(name, model.lo, model.hi, core::BoxMode::Keep),
                    [&wb, name] { wb.selection().box = name; });
        }
        wb.mark("boxes.add");
        ImGui::EndDisabled();
        const core::CuttingBox* sel = s.box(wb.selection().box);
        flowSameLine(buttonWidth("Duplicate"));
        ImGui::BeginDisabled(!sel);
        if (ImGui::Button("Duplicate") && sel) {
            const std::string name = uniqueName(s, sel->name);
            core::CuttingBox copy = *sel;
            copy.name = name;
            wb.emit(core::cmd::boxAdd(copy), [&wb, name] { wb.selection().box = name; });
        }
        wb.mark("boxes.duplicate");
        flowSameLine(buttonWidth("Delete"));
        if (ImGui::Button("Delete") && sel)
            wb.emit(core::cmd::boxRemove(sel->name));
        wb.mark("boxes.delete");
        ImGui::EndDisabled();
        flowSameLine(checkboxWidth("Edit in view"));
        ImGui::Checkbox("Edit in view", &wb.selection().editBoxInView);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Show the selected box's face handles in the viewports; drag them to move a face.");

        if (s.boxes.empty()) {
            ImGui::Spacing();
            hint("No boxes. A keep box shows only what lies inside it; a cut box hides what lies "
                 "inside it.");
            return;
        }
        // The list.
        const float rowH = ImGui::GetFrameHeightWithSpacing();
        const float listH =
            std::min<float>(static_cast<float>(s.boxes.size()) * rowH + rowH, 7.5f * rowH);
        if (beginScrollingTable("##boxes", 3,
                                ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter |
                                    ImGuiTableFlags_ScrollY,
                                listH)) {
            ImGui::TableSetupColumn("on", ImGuiTableColumnFlags_WidthFixed,
                                    ImGui::GetFrameHeight());
            ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthStretch);
            ImGui::TableSetupColumn("mode", ImGuiTableColumnFlags_WidthFixed, 70 * wb.scale());
            for (const core::CuttingBox& b : s.boxes) {
                ImGui::PushID(b.name.c_str());
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                bool enabled = b.enabled;
                if (ImGui::Checkbox("##on", &enabled))
                    wb.emit(core::cmd::BoxSet(b.name).enabled(enabled));
                wb.mark("boxes.enabled." + b.name);
                ImGui::TableNextColumn();
                ImGui::AlignTextToFramePadding();
                const std::string shown = elided(b.name, ImGui::GetContentRegionAvail().x);
                if (ImGui::Selectable((shown + "##row").c_str(), b.name == wb.selection().box,
                                      ImGuiSelectableFlags_SpanAllColumns |
                                          ImGuiSelectableFlags_AllowItemOverlap))
                    wb.selection().box = b.name;
                if (shown != b.name && ImGui::IsItemHovered())
                    ImGui::SetTooltip("%s", b.name.c_str());
                wb.mark("boxes.row." + b.name);
                ImGui::TableNextColumn();
                ImGui::TextColored(b.mode == core::BoxMode::Keep ? ImVec4(0.15f, 0.5f, 0.25f, 1)
                                                                 : ImVec4(0.75f, 0.25f, 0.15f, 1),
                                   "%s", b.mode == core::BoxMode::Keep ? "keep" : "cut");
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
        sel = s.box(wb.selection().box);
        if (!sel) {
            hint("Select a box to edit it.");
            return;
        }
        drawEditor(wb, *sel, model);
    }

  private:
    void drawEditor(PanelContext& wb, const core::CuttingBox& b, const ModelBounds& model) {
        ImGui::Spacing();
        sectionHeader("Box \"" + b.name + "\"");
        if (m_nameFor != b.name) {
            m_name = b.name;
            m_nameFor = b.name;
        }
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Name");
        ImGui::SameLine(ImGui::GetFontSize() * 4);
        ImGui::SetNextItemWidth(-1);
        ImGui::InputText("##name", &m_name);
        if (ImGui::IsItemDeactivatedAfterEdit() && !m_name.empty() && m_name != b.name) {
            const std::string next = m_name;
            wb.emit(core::cmd::BoxSet(b.name).rename(next),
                    [&wb, next] { wb.selection().box = next; });
        }
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Mode");
        ImGui::SameLine(ImGui::GetFontSize() * 4);
        int mode = b.mode == core::BoxMode::Keep ? 0 : 1;
        if (ImGui::RadioButton("keep inside", &mode, 0) && b.mode != core::BoxMode::Keep)
            wb.emit(core::cmd::BoxSet(b.name).mode(core::BoxMode::Keep));
        ImGui::SameLine();
        if (ImGui::RadioButton("cut inside", &mode, 1) && b.mode != core::BoxMode::Cut)
            wb.emit(core::cmd::BoxSet(b.name).mode(core::BoxMode::Cut));
        wb.mark("boxes.mode.cut");

        const char* axes[3] = {"x (east)", "y (north)", "z (up)"};
        if (m_dragFor != b.name)
            m_drag.reset(), m_dragFor = b.name;
        for (int a = 0; a < 3; ++a) {
            ImGui::PushID(a);
            ImGui::Spacing();
            ImGui::TextDisabled("%s", axes[a]);
            const float half =
                (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
            double lo = b.min[a], hi = b.max[a];
            const bool minTyped = numberField("##min", &lo, "%.6g", half);
            wb.mark("boxes.min." + std::to_string(a));
            if (minTyped && lo != b.min[a]) {
                auto mn = b.min;
                mn[a] = std::min(lo, b.max[a]);
                wb.emit(core::cmd::BoxSet(b.name).min(mn));
            }
            ImGui::SameLine();
            const bool maxTyped = numberField("##max", &hi, "%.6g", half);
            wb.mark("boxes.max." + std::to_string(a));
            if (maxTyped && hi != b.max[a]) {
                auto mx = b.max;
                mx[a] = std::max(hi, b.min[a]);
                wb.emit(core::cmd::BoxSet(b.name).max(mx));
            }
            // Fractions of the model's extent on this axis.
            const double extent = std::max(model.hi[a] - model.lo[a], 1e-12);
            if (!m_drag || m_drag->axis != a) {
                m_frac[a][0] = (b.min[a] - model.lo[a]) / extent;
                m_frac[a][1] = (b.max[a] - model.lo[a]) / extent;
            }
            const RangeEdit e =
                rangeSlider("##frac", &m_frac[a][0], &m_frac[a][1], 0.0, 1.0, false, -1, "%.2f");
            wb.mark("boxes.fraction." + std::to_string(a));
            if (e.changed)
                m_drag = Drag{a};
            if (m_drag && m_drag->axis == a) {
                auto mn = b.min, mx = b.max;
                mn[a] = model.lo[a] + m_frac[a][0] * extent;
                mx[a] = model.lo[a] + m_frac[a][1] * extent;
                const core::Json cmd = core::cmd::BoxSet(b.name).min(mn).max(mx);
                if (e.released) {
                    wb.emit(cmd);
                    m_drag.reset();
                } else {
                    wb.preview("box." + b.name, cmd);
                }
            }
            ImGui::PopID();
        }
    }

    struct Drag {
        int axis = 0;
    };
    std::optional<Drag> m_drag;
    std::string m_dragFor;
    double m_frac[3][2] = {{0, 1}, {0, 1}, {0, 1}};
    std::string m_name, m_nameFor;
};

} // namespace

std::unique_ptr<Panel> makeBoxesPanel() { return std::make_unique<BoxesPanel>(); }

} // namespace faultline::ui
