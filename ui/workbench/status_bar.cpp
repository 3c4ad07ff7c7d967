#include "ui/workbench/status_bar.hpp"

#include "core/data/dataset.hpp"
#include "ui/context/panel_context.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace faultline::ui {

void StatusBar::draw(PanelContext& ctx, float height) {
    const float scale = ctx.scale();
    const double now = ctx.now();
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, io.DisplaySize.y - height));
    ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, height));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8 * scale, 4 * scale));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImGui::GetColorU32(ImGuiCol_MenuBarBg));
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                     ImGuiWindowFlags_NoNavFocus);
    ImGui::PopStyleColor();
    ImGui::PopStyleVar(2);
    ImGui::AlignTextToFramePadding();

    // Right: where we are.
    std::string where;
    if (auto ds = ctx.dataset()) {
        const ViewDisplay* main = ctx.mainDisplay();
        const std::size_t f = ctx.displayFrame();
        char buf[160];
        std::snprintf(buf, sizeof buf, "frame %zu / %zu   timestep %lld", f, ds->frameCount(),
                      static_cast<long long>(ds->location(f).timestep));
        where = buf;
        if (main && main->frame && main->visibility) {
            std::snprintf(buf, sizeof buf, "   %zu of %zu spheres visible",
                          main->visibility->visibleCount, main->frame->size());
            where += buf;
        }
    } else {
        where = "no data open";
    }
    const float whereW = ImGui::CalcTextSize(where.c_str()).x;

    // Left: background work, then the last message.
    auto jobs = ctx.jobs().running();
    for (auto& job : jobs) {
        ImGui::PushID(job.get());
        ImGui::TextUnformatted(job->title().c_str());
        ImGui::SameLine();
        const float p = job->progress();
        ImGui::SetNextItemWidth(160 * scale);
        if (p >= 0)
            ImGui::ProgressBar(p, ImVec2(160 * scale, 0));
        else
            ImGui::ProgressBar(static_cast<float>(std::fmod(now - job->startTime(), 1.0)),
                               ImVec2(160 * scale, 0), "working...");
        ImGui::SameLine();
        if (ImGui::SmallButton(job->cancelRequested() ? "cancelling" : "Cancel"))
            job->cancel();
        ctx.items().markLastItem("status.cancel");
        ImGui::SameLine();
        ImGui::PopID();
    }
    if (auto loading = ctx.frames().loading()) {
        ImGui::TextDisabled("loading frame %zu...", *loading);
        ImGui::SameLine();
    }
    const std::string frameError = ctx.frames().lastError();
    const bool showMessage = !m_message.empty() && (m_isError || now - m_time < 10.0);
    const std::string& message = frameError.empty() ? m_message : frameError;
    if (showMessage || !frameError.empty()) {
        const bool isError = !frameError.empty() || m_isError;
        const float avail = ImGui::GetContentRegionAvail().x - whereW - 24 * scale;
        ImGui::PushClipRect(ImGui::GetCursorScreenPos(),
                            ImVec2(ImGui::GetCursorScreenPos().x + std::max(0.0f, avail),
                                   ImGui::GetCursorScreenPos().y + height),
                            true);
        if (isError)
            ImGui::TextColored(ImVec4(0.80f, 0.16f, 0.12f, 1.0f), "%s", message.c_str());
        else
            ImGui::TextUnformatted(message.c_str());
        ImGui::PopClipRect();
        if (ImGui::IsItemHovered()) { // the whole message, wrapped
            ImGui::BeginTooltip();
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
            ImGui::TextUnformatted(message.c_str());
            ImGui::PopTextWrapPos();
            ImGui::EndTooltip();
        }
        ctx.items().markLastItem("status.message");
        ImGui::SameLine();
    }
    ImGui::SameLine(
        std::max(ImGui::GetCursorPosX(), ImGui::GetWindowWidth() - whereW - 10 * scale));
    ImGui::TextUnformatted(where.c_str());
    ImGui::End();
}

} // namespace faultline::ui
