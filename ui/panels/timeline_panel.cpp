// Timeline panel: scrub the frames (the slider marks the frames already loaded), play/pause at a
// chosen rate, step, loop, jump. Scrubbing and playing show frames at once; the session's frame
// changes by one frame.set when the slider is released or playback pauses.
#include "core/session/commands.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/icon_button.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace faultline::ui {

namespace {

constexpr double kRates[] = {1, 2, 5, 10, 15, 24, 30, 60};

class TimelinePanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kTimeline; }
    const char* title() const override { return "Timeline"; }

    void draw(PanelContext& wb) override {
        auto ds = wb.dataset();
        Playback& pb = wb.playback();
        const std::size_t count = ds ? ds->frameCount() : 0;
        const std::size_t shown = wb.displayFrame();
        ImGui::BeginDisabled(count < 2);
        if (iconButton("##first", Icon::First, "First frame (Home)"))
            wb.jumpToFrame(0);
        ImGui::SameLine(0, 2);
        if (iconButton("##prev", Icon::Previous, "Previous frame (Left; Shift: 10)"))
            wb.stepFrames(-1);
        wb.mark("timeline.prev");
        ImGui::SameLine(0, 2);
        if (iconButton("##play", pb.playing ? Icon::Pause : Icon::Play,
                       pb.playing ? "Pause (Space)" : "Play (Space)"))
            pb.playing ? wb.pause() : wb.play();
        wb.mark("timeline.play");
        ImGui::SameLine(0, 2);
        if (iconButton("##next", Icon::Next, "Next frame (Right; Shift: 10)"))
            wb.stepFrames(1);
        wb.mark("timeline.next");
        ImGui::SameLine(0, 2);
        if (iconButton("##last", Icon::Last, "Last frame (End)"))
            wb.jumpToFrame(static_cast<long long>(count) - 1);
        ImGui::SameLine();
        drawScrubber(wb, count, shown);
        ImGui::EndDisabled();

        // Second row: where we are, rate, loop, jump.
        if (ds) {
            ImGui::AlignTextToFramePadding();
            ImGui::Text("frame %zu of %zu", shown, count);
            ImGui::SameLine();
            ImGui::TextDisabled(
                "timestep %lld",
                static_cast<long long>(ds->location(std::min(shown, count - 1)).timestep));
            const ViewDisplay* main = wb.mainDisplay();
            if (main && main->loading()) {
                ImGui::SameLine();
                ImGui::TextDisabled("(loading...)");
            }
        } else {
            ImGui::AlignTextToFramePadding();
            ImGui::TextDisabled("no data");
        }
        // Rate, loop and jump at the right end of the row; below the text when the panel is too
        // narrow for both (issue 41: at 640x420 they were drawn over "frame 39 of 40").
        const ImGuiStyle& style = ImGui::GetStyle();
        const float right =
            80 * wb.scale() + checkboxWidth("Loop") + 60 * wb.scale() + 2 * style.ItemSpacing.x;
        const float textEnd = ImGui::GetItemRectMax().x - ImGui::GetWindowPos().x;
        if (textEnd + 12 * wb.scale() + right <= ImGui::GetContentRegionMax().x)
            ImGui::SameLine(
                std::max(textEnd + 12 * wb.scale(), ImGui::GetContentRegionMax().x - right));
        ImGui::SetNextItemWidth(80 * wb.scale());
        char rate[32];
        std::snprintf(rate, sizeof rate, "%g fps", pb.fps);
        if (ImGui::BeginCombo("##rate", rate)) {
            for (double r : kRates) {
                std::snprintf(rate, sizeof rate, "%g fps", r);
                if (ImGui::Selectable(rate, r == pb.fps))
                    pb.fps = r;
            }
            ImGui::EndCombo();
        }
        ImGui::SameLine();
        ImGui::Checkbox("Loop", &pb.loop);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(std::max(60 * wb.scale(), ImGui::GetContentRegionAvail().x));
        int jump = static_cast<int>(shown);
        ImGui::BeginDisabled(count < 2);
        if (ImGui::InputInt("##jump", &jump, 0, 0, ImGuiInputTextFlags_EnterReturnsTrue))
            wb.jumpToFrame(jump);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Go to frame (Enter)");
        wb.mark("timeline.jump");
        ImGui::EndDisabled();
    }

  private:
    void drawScrubber(PanelContext& wb, std::size_t count, std::size_t shown) {
        const float w = std::max(40.0f, ImGui::GetContentRegionAvail().x);
        const float h = ImGui::GetFrameHeight();
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        ImGui::InvisibleButton("##scrub", ImVec2(w, h));
        wb.mark("timeline.slider");
        const bool active = ImGui::IsItemActive(), hovered = ImGui::IsItemHovered();
        ImDrawList* dl = ImGui::GetWindowDrawList();
        const float pad = h * 0.5f;
        const float x0 = p0.x + pad, x1 = p0.x + w - pad;
        auto toX = [&](std::size_t f) {
            return count < 2
                       ? x0
                       : x0 + (x1 - x0) * static_cast<float>(f) / static_cast<float>(count - 1);
        };
        dl->AddRectFilled(
            p0, ImVec2(p0.x + w, p0.y + h),
            ImGui::GetColorU32(hovered || active ? ImGuiCol_FrameBgHovered : ImGuiCol_FrameBg),
            ImGui::GetStyle().FrameRounding);
        const float cy = p0.y + h * 0.5f;
        dl->AddLine(ImVec2(x0, cy), ImVec2(x1, cy), ImGui::GetColorU32(ImGuiCol_Border), 2);
        // Loaded frames as marks under the track.
        if (count >= 2 && count <= 4000)
            for (std::size_t f = 0; f < count; ++f)
                if (wb.frames().isLoaded(f)) {
                    const float x = toX(f);
                    dl->AddLine(ImVec2(x, cy + 3), ImVec2(x, p0.y + h - 3),
                                ImGui::GetColorU32(ImGuiCol_PlotHistogram, 0.55f), 2);
                }
        if (count >= 2 && active) {
            const float mx = std::clamp(ImGui::GetIO().MousePos.x, x0, x1);
            const auto f = static_cast<std::size_t>(
                std::lround((mx - x0) / (x1 - x0) * static_cast<float>(count - 1)));
            m_scrub = f;
            if (wb.playback().playing)
                wb.playback().frame = f;
            else
                wb.preview("timeline.scrub", core::cmd::frameSet(f));
        }
        if (ImGui::IsItemDeactivated() && m_scrub) {
            if (!wb.playback().playing)
                wb.jumpToFrame(static_cast<long long>(*m_scrub));
            m_scrub.reset();
        }
        if (count >= 1) {
            const std::size_t at = m_scrub.value_or(shown);
            const float x = toX(std::min(at, count - 1));
            dl->AddRectFilled(
                ImVec2(x - 5, p0.y + 2), ImVec2(x + 5, p0.y + h - 2),
                ImGui::GetColorU32(active ? ImGuiCol_SliderGrabActive : ImGuiCol_SliderGrab), 3);
        }
        if (hovered && count >= 2 && !active) {
            const float mx = std::clamp(ImGui::GetIO().MousePos.x, x0, x1);
            const auto f = static_cast<std::size_t>(
                std::lround((mx - x0) / (x1 - x0) * static_cast<float>(count - 1)));
            ImGui::SetTooltip("frame %zu, timestep %lld", f,
                              static_cast<long long>(wb.dataset()->location(f).timestep));
        }
    }

    std::optional<std::size_t> m_scrub;
};

} // namespace

std::unique_ptr<Panel> makeTimelinePanel() { return std::make_unique<TimelinePanel>(); }

} // namespace faultline::ui
