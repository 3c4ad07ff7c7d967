// Faults panel, "Candidates": linked groups of the visible spheres (k x (r_i + r_j)), found on
// request and shown in distinct colours in the main view, largest first; the user accepts one as
// a named fault (fault.create), or all at once (the journal's fault.candidates).
#include "core/motion/strain_spec.hpp"
#include "core/session/commands.hpp"
#include "ui/panels/panels.hpp"
#include "ui/viewport/fault_edit.hpp"
#include "ui/widgets/number_field.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <unordered_map>

namespace faultline::ui {

namespace {

// What to threshold on to narrow the spheres to their faults: the shear strain from motion,
// else a damage column the file has.
std::string narrowingHint(PanelContext& wb, const core::Frame& frame) {
    for (const core::StrainSpec& spec : wb.state().strains)
        if (const std::string v = spec.variable(core::kShearStrain); frame.attribute(v))
            return "a threshold on " + v + " (Histograms or Thresholds)";
    for (const char* v : {"broken_bonds", "strain", "damage"})
        if (frame.attribute(v))
            return std::string("a threshold on ") + v + " (Histograms or Thresholds)";
    return "strain from motion (Data panel), then a threshold on its shear strain";
}

class FaultCandidatesSection {
  public:
    void draw(PanelContext& wb) {
        const ViewDisplay* main = wb.mainDisplay();
        const bool ready = main && main->frame && main->visibility;
        numberField("link k", &m_link, "%.2f", ImGui::GetFontSize() * 5);
        m_link = std::clamp(m_link, 0.5, 5.0);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Two spheres are linked when their centres are closer than k x (r_i + r_j)");
        flowSameLine(labelledWidth(ImGui::GetFontSize() * 5, "min size"));
        numberField("min size", &m_minSize, ImGui::GetFontSize() * 5);
        m_minSize = std::max(1, m_minSize);
        ImGui::Checkbox("Apart at junctions", &m_network);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Follow each fault by its orientation: faults that cross or end against\n"
                "each other come out apart (off: linked spheres by distance alone)");
        if (m_network) {
            flowSameLine(labelledWidth(ImGui::GetFontSize() * 4, "angle"));
            numberField("angle", &m_angle, "%.0f", ImGui::GetFontSize() * 4);
            m_angle = std::clamp(m_angle, 1.0, 89.0);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Degrees: the largest turn of orientation within one fault");
        }
        const bool finding = m_finding && !m_finding->finished();
        ImGui::BeginDisabled(!ready || main->visibility->visibleCount == 0 || finding);
        if (ImGui::Button(finding ? "Finding..." : "Find in visible"))
            find(wb, *main);
        wb.mark("candidates.find");
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip(
                "Groups of linked visible spheres (narrow them first, e.g. broken bonds >= 1)");

        auto& preview = wb.selection().candidates;
        if (!preview)
            return;
        flowSameLine(buttonWidth("Clear"));
        if (ImGui::Button("Clear"))
            return clear(wb);
        wb.mark("candidates.clear");
        // Found with nothing narrowed: the groups are pieces of the whole model, not faults (a
        // walkthrough on LIGGGHTS' run: three slabs of the block).
        if (preview->visibility && preview->frame &&
            preview->visibility->visibleCount == preview->frame->size()) {
            hint("Every sphere was visible: groups of the whole model are pieces of it, not "
                 "faults. Narrow the spheres first: %s.",
                 narrowingHint(wb, *preview->frame).c_str());
            wb.mark("candidates.all_visible");
        }
        const auto& cands = preview->set.candidates;
        if (cands.empty()) {
            ImGui::TextDisabled(preview->options.method == core::CandidateMethod::Network
                                    ? "No fault of %d or more visible spheres."
                                    : "No group of %d or more linked visible spheres.",
                                m_minSize);
            return;
        }
        // Stale once the visible spheres differ (not merely because another command ran).
        const bool stale = !ready || main->frame != preview->frame ||
                           (main->visibility != preview->visibility &&
                            main->visibility->mask != preview->visibility->mask);
        hint("%zu candidates (%.0f ms)%s", cands.size(), m_millis,
             stale ? ": the visible spheres changed, find again" : ", shown in the main view");
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4);
        ImGui::InputText("prefix", &m_prefix);
        flowSameLine(buttonWidth("Accept all"));
        ImGui::BeginDisabled(stale || m_prefix.empty());
        if (ImGui::Button("Accept all")) {
            core::cmd::FaultCandidates cmd;
            cmd.link(preview->options.link)
                .minSize(static_cast<long long>(preview->options.minSize))
                .prefix(m_prefix);
            if (preview->options.method == core::CandidateMethod::Connected)
                cmd.method(core::CandidateMethod::Connected);
            else if (preview->options.angle != core::kDefaultCandidateAngle)
                cmd.angle(preview->options.angle);
            std::vector<std::int64_t> all; // every candidate's spheres, into new faults
            for (const auto& c : preview->set.candidates)
                all.insert(all.end(), c.ids.begin(), c.ids.end());
            core::Json accept = withEmptiedRemoved(wb.state(), cmd, std::move(all), {});
            // The op finds candidates in the session's current frame, the preview was found in
            // the frame the main view shows (a view offset, a fixed frame, playback). Where they
            // differ, the op runs at the previewed frame and the current frame comes back after
            // it, in one undo step: the faults made are those shown (issue 39).
            if (const std::size_t current = wb.state().frame; main->shownFrame != current)
                accept = core::cmd::batch(
                    {core::cmd::frameSet(main->shownFrame), accept, core::cmd::frameSet(current)});
            wb.emit(accept, [&wb] { wb.selection().candidates.reset(); });
        }
        wb.mark("candidates.accept_all");
        ImGui::EndDisabled();

        updateOverlaps(wb, *preview);
        const float rowH = ImGui::GetFrameHeightWithSpacing();
        const float h = std::min(rowH * (static_cast<float>(cands.size()) + 0.5f), rowH * 8.0f);
        if (!beginScrollingTable("##candidates", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                                 h))
            return;
        ImGui::TableSetupColumn("c", ImGuiTableColumnFlags_WidthFixed, ImGui::GetFrameHeight());
        ImGui::TableSetupColumn("size", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableSetupColumn("accept", ImGuiTableColumnFlags_WidthFixed,
                                ImGui::CalcTextSize("Accepted").x + 12);
        ImGuiListClipper clipper;
        clipper.Begin(static_cast<int>(cands.size()));
        while (clipper.Step())
            for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
                ImGui::PushID(k);
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                const glm::vec3 c = preview->coloring.palette[static_cast<std::size_t>(k) + 1];
                ImGui::ColorButton("##c", ImVec4(c.r, c.g, c.b, 1),
                                   ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoPicker,
                                   ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
                ImGui::TableNextColumn();
                // What follows the size wraps in its cell rather than run under Accept (a
                // walkthrough: "shares N" was hidden at the default width).
                const float cellRight =
                    ImGui::GetCursorScreenPos().x + ImGui::GetContentRegionAvail().x;
                const auto besideOrBelow = [cellRight](const char* text) {
                    if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x +
                            ImGui::CalcTextSize(text).x <=
                        cellRight)
                        ImGui::SameLine();
                };
                ImGui::Text("#%d  %zu", k + 1, cands[static_cast<std::size_t>(k)].size());
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%zu spheres", cands[static_cast<std::size_t>(k)].size());
                if (static_cast<std::size_t>(k) < preview->shapes.size()) {
                    const core::CandidateShape& shape =
                        preview->shapes[static_cast<std::size_t>(k)];
                    if (shape.valid) {
                        char orientation[32];
                        std::snprintf(orientation, sizeof orientation, "%.0f%s/%03.0f", shape.dip,
                                      "\xC2\xB0", shape.dipDirection);
                        besideOrBelow(orientation);
                        ImGui::TextDisabled("%s", orientation);
                        if (ImGui::IsItemHovered())
                            ImGui::SetTooltip("dip / dip direction (degrees)");
                    }
                    if (shape.diffuse) {
                        besideOrBelow("diffuse");
                        ImGui::TextColored(ImVec4(0.85f, 0.45f, 0.05f, 1), "diffuse");
                        if (ImGui::IsItemHovered())
                            ImGui::SetTooltip(
                                "Its spheres fill a volume (thickness %.2f of its width) rather\n"
                                "than a sheet: distributed damage, not one fault plane, so its\n"
                                "dip says little. Accepted, the fault's notes say so.",
                                shape.thicknessRatio);
                    }
                    if (shape.valid && shape.subHorizontal) {
                        besideOrBelow("flat");
                        ImGui::TextColored(ImVec4(0.2f, 0.45f, 0.75f, 1), "flat");
                        wb.mark("candidates.flat." + std::to_string(k + 1));
                        if (ImGui::IsItemHovered())
                            ImGui::SetTooltip(
                                "Sub-horizontal (dips %.0f degrees): in a stretched or shortened\n"
                                "block more often a layer along its free surface (which creeps)\n"
                                "or its base than a fault; in a shear box, the shear zone.\n"
                                "Accepted, the fault's notes say so.",
                                shape.dip);
                    }
                }
                if (const std::size_t kk = static_cast<std::size_t>(k);
                    kk < m_overlaps.size() && !m_overlaps[kk].empty() && !m_accepted.count(k)) {
                    // Issue 41: accepting takes these spheres out of the faults they are in;
                    // say so before the click, not only in the status line after it.
                    std::size_t shared = 0;
                    std::string where;
                    for (const auto& [fault, n] : m_overlaps[kk]) {
                        shared += n;
                        where +=
                            (where.empty() ? "" : ", ") + fault + " (" + std::to_string(n) + ")";
                    }
                    char sharesText[32];
                    std::snprintf(sharesText, sizeof sharesText, "shares %zu", shared);
                    besideOrBelow(sharesText);
                    ImGui::TextColored(ImVec4(0.85f, 0.45f, 0.05f, 1), "%s", sharesText);
                    wb.mark("candidates.overlap." + std::to_string(k + 1));
                    if (ImGui::IsItemHovered())
                        ImGui::SetTooltip(
                            "%zu of its spheres are in %s.\nAccepting moves them into "
                            "the new fault (undo gives them back).",
                            shared, where.c_str());
                }
                ImGui::TableNextColumn();
                const bool done = m_accepted.count(k) > 0;
                ImGui::BeginDisabled(done || stale);
                if (ImGui::SmallButton(done ? "Accepted" : "Accept"))
                    accept(wb, k);
                wb.mark("candidates.accept." + std::to_string(k + 1));
                ImGui::EndDisabled();
                ImGui::PopID();
            }
        ImGui::EndTable();
    }

  private:
    // The journal's defaults. Accept all's prefix is not the "F" of faults made by hand (and of a
    // single accepted candidate): fault.candidates refuses names that exist.
    double m_link = core::kDefaultCandidateLink;
    int m_minSize = static_cast<int>(core::kDefaultCandidateMinSize);
    bool m_network = true;
    double m_angle = core::kDefaultCandidateAngle;
    std::string m_prefix{core::kDefaultCandidatePrefix};
    double m_millis = 0;
    std::set<int> m_accepted;
    std::shared_ptr<Job> m_finding;

    // Clustering a million visible spheres takes a while: a background job (progress in the
    // status bar, cancel there); the preview appears when it is done.
    void find(PanelContext& wb, const ViewDisplay& main) {
        core::CandidateOptions options;
        options.link = m_link;
        options.minSize = static_cast<std::size_t>(m_minSize);
        options.method =
            m_network ? core::CandidateMethod::Network : core::CandidateMethod::Connected;
        options.angle = m_angle;
        if (m_finding && !m_finding->finished())
            m_finding->cancel();
        m_finding = wb.jobs().start(
            "Finding fault candidates",
            [this, &wb, options, frame = main.frame, visibility = main.visibility,
             prefix = m_prefix](JobControl&) -> std::function<void()> {
                const auto t0 = std::chrono::steady_clock::now();
                UiSelection::CandidatePreview p;
                p.frame = frame;
                p.visibility = visibility;
                p.options = options;
                p.set = core::findCandidates(*frame, visibility->mask, options);
                p.coloring = candidateColoring(p.set.rowLabel, p.set.candidates.size(), prefix);
                for (const auto& c : p.set.candidates)
                    p.shapes.push_back(core::candidateShape(*frame, c.ids));
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
                auto shared = std::make_shared<UiSelection::CandidatePreview>(std::move(p));
                return [this, &wb, shared, ms] {
                    m_millis = ms;
                    m_accepted.clear();
                    m_overlapsVersion = ~0ull; // a new preview: its overlaps are worked out anew
                    wb.selection().candidates = std::move(*shared);
                };
            },
            [&wb](const std::string& why) { wb.error("Cannot find candidates: " + why); },
            wb.now());
    }

    // Per candidate, the faults that hold some of its spheres and how many: worked out again
    // when the session or the preview changes (one pass over the faults' and candidates' ids).
    std::vector<std::vector<std::pair<std::string, std::size_t>>> m_overlaps;
    std::uint64_t m_overlapsVersion = ~0ull;
    const core::CandidateSet* m_overlapsSet = nullptr;

    void updateOverlaps(PanelContext& wb, const UiSelection::CandidatePreview& preview) {
        if (m_overlapsVersion == wb.sessionVersion() && m_overlapsSet == &preview.set &&
            m_overlaps.size() == preview.set.candidates.size())
            return;
        m_overlapsVersion = wb.sessionVersion();
        m_overlapsSet = &preview.set;
        const auto& faults = wb.state().faults;
        std::unordered_map<std::int64_t, std::size_t> owner; // id -> fault index
        for (std::size_t f = 0; f < faults.size(); ++f)
            for (std::int64_t id : faults[f].ids)
                owner.emplace(id, f);
        m_overlaps.assign(preview.set.candidates.size(), {});
        if (owner.empty())
            return;
        std::vector<std::size_t> counts(faults.size());
        for (std::size_t c = 0; c < preview.set.candidates.size(); ++c) {
            std::fill(counts.begin(), counts.end(), 0);
            for (std::int64_t id : preview.set.candidates[c].ids)
                if (auto it = owner.find(id); it != owner.end())
                    ++counts[it->second];
            for (std::size_t f = 0; f < faults.size(); ++f)
                if (counts[f] > 0)
                    m_overlaps[c].emplace_back(faults[f].name, counts[f]);
        }
    }

    void clear(PanelContext& wb) {
        wb.selection().candidates.reset();
        m_accepted.clear();
    }

    void accept(PanelContext& wb, int k) {
        const auto& cand = wb.selection().candidates->set.candidates[static_cast<std::size_t>(k)];
        // Named as the list and the legend call it (prefix + number), unless that name is taken.
        std::string name = m_prefix + std::to_string(k + 1);
        if (m_prefix.empty() || wb.state().fault(name))
            name = nextFaultName(wb.state());
        const auto color = core::candidateColor(static_cast<std::size_t>(k));
        core::cmd::FaultCreate cmd(name, cand.ids);
        cmd.color(color);
        const auto& shapes = wb.selection().candidates->shapes;
        if (static_cast<std::size_t>(k) < shapes.size())
            if (std::string note = core::shapeNote(shapes[static_cast<std::size_t>(k)]);
                !note.empty())
                cmd.notes(note);
        wb.emit(withEmptiedRemoved(wb.state(), cmd, cand.ids, name), [this, &wb, k, name] {
            m_accepted.insert(k);
            wb.selection().faults = {name};
        });
    }
};

} // namespace

void addFaultCandidatesSection(PanelExtensions& extensions) {
    auto section = std::make_shared<FaultCandidatesSection>();
    extensions.faultSections.push_back(
        {"Candidates", [section](PanelContext& wb) { section->draw(wb); }, true});
}

} // namespace faultline::ui
