// Thresholds panel: one row per variable threshold: enabled, low/high as numbers and on a range
// slider over the variable's values in the current frame; add on any variable, remove.
#include "core/session/commands.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/bound_input.hpp"
#include "ui/widgets/range_slider.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include "core/selection/column_view.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace faultline::ui {

namespace {

class ThresholdsPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kThresholds; }
    const char* title() const override { return "Thresholds"; }

    void draw(PanelContext& wb) override {
        const ViewDisplay* main = wb.mainDisplay();
        const core::Frame* frame = main && main->frame ? main->frame.get() : nullptr;
        const float scale = wb.scale();

        // Add a threshold on a variable that has none.
        ImGui::BeginDisabled(!frame);
        const float comboW = std::min(ImGui::GetContentRegionAvail().x, 220 * scale);
        ImGui::SetNextItemWidth(comboW);
        const std::string addLabel =
            elided("Add a threshold on...",
                   comboW - ImGui::GetFrameHeight() - 2 * ImGui::GetStyle().FramePadding.x);
        if (ImGui::BeginCombo("##addthreshold", addLabel.c_str())) {
            if (frame)
                for (const auto& [v, vinfo] : wb.columns().of(main->frame)) {
                    if (wb.state().threshold(v))
                        continue;
                    const bool chosen = ImGui::Selectable(v.c_str());
                    wb.mark("thresholds.add." + v);
                    if (chosen) {
                        core::cmd::ThresholdAdd cmd(v);
                        if (vinfo.min <= vinfo.max)
                            cmd.low(vinfo.min).high(vinfo.max);
                        wb.emit(cmd);
                    }
                }
            ImGui::EndCombo();
        }
        wb.mark("thresholds.add");
        ImGui::EndDisabled();
        ImGui::Spacing();
        if (wb.state().thresholds.empty()) {
            hint("No thresholds. Add one above, or drag across a histogram.");
            return;
        }
        std::string toRemove;
        for (const core::VariableThreshold& t : wb.state().thresholds) {
            ImGui::PushID(t.variable.c_str());
            ImGui::Separator();
            bool enabled = t.enabled;
            if (ImGui::Checkbox("##enabled", &enabled))
                wb.emit(core::cmd::ThresholdSet(t.variable).enabled(enabled));
            wb.mark("thresholds.enabled." + t.variable);
            ImGui::SameLine();
            VariableInfo info{};
            bool haveInfo = false;
            if (frame)
                if (auto i = wb.columns().info(main->frame, t.variable))
                    info = *i, haveInfo = true;
            const float removeW =
                ImGui::CalcTextSize("Remove").x + ImGui::GetStyle().FramePadding.x * 2;
            // A long name in a narrow panel ends in "..." before Remove (all of it on hover);
            // in a very narrow one Remove goes on the next row, so the name keeps its room.
            const float room = ImGui::GetContentRegionMax().x - removeW - ImGui::GetCursorPosX() -
                               ImGui::GetStyle().ItemSpacing.x;
            const bool removeBeside = room >= std::min(ImGui::CalcTextSize(t.variable.c_str()).x,
                                                       ImGui::GetFontSize() * 6);
            textElided(t.variable, removeBeside ? std::max(1.0f, room) : 0.0f);
            if (removeBeside)
                ImGui::SameLine(ImGui::GetContentRegionMax().x - removeW);
            if (ImGui::SmallButton("Remove"))
                toRemove = t.variable;
            wb.mark("thresholds.remove." + t.variable);
            // Issue 41: a typo ("strian") or data without the column must not pass silently.
            if (frame && !haveInfo) {
                const std::string note =
                    core::missingVariableNote(*frame, t.variable) + ": this threshold is ignored";
                ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.45f, 0.1f, 1));
                ImGui::TextWrapped("%s", note.c_str());
                ImGui::PopStyleColor();
                wb.mark("thresholds.missing." + t.variable);
            }

            const bool integer = haveInfo && info.integer;
            // Numbers: committed when the field is left or Enter pressed; empty is open-ended.
            double low = t.low, high = t.high;
            const float half =
                (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
            if (boundInput("low", &low, false, integer, half))
                wb.emit(core::cmd::ThresholdSet(t.variable).low(low));
            wb.mark("thresholds.low." + t.variable);
            ImGui::SameLine();
            if (boundInput("high", &high, true, integer, half))
                wb.emit(core::cmd::ThresholdSet(t.variable).high(high));
            wb.mark("thresholds.high." + t.variable);

            // Slider over the variable's range in this frame.
            if (haveInfo && info.min <= info.max) {
                auto& drag = m_drag[t.variable];
                if (!drag.active)
                    drag.lo = t.low, drag.hi = t.high;
                const RangeEdit e =
                    rangeSlider("##slider", &drag.lo, &drag.hi, info.min, info.max, integer, -1);
                wb.mark("thresholds.slider." + t.variable);
                if (e.changed)
                    drag.active = true;
                const core::Json cmd =
                    core::cmd::ThresholdSet(t.variable).low(drag.lo).high(drag.hi);
                if (drag.active && !e.released)
                    wb.preview("threshold." + t.variable, cmd);
                if (e.released && drag.active) {
                    wb.emit(cmd);
                    drag.active = false;
                }
            }
            ImGui::PopID();
        }
        if (!toRemove.empty())
            wb.emit(core::cmd::thresholdRemove(toRemove));
    }

  private:
    struct Drag {
        double lo = 0, hi = 0;
        bool active = false;
    };
    std::map<std::string, Drag> m_drag;
};

} // namespace

std::unique_ptr<Panel> makeThresholdsPanel() { return std::make_unique<ThresholdsPanel>(); }

} // namespace faultline::ui
