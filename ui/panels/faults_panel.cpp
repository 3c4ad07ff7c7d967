// Faults panel: the table of named faults (visibility, colour, name, size, notes), creating one
// from the visible spheres, adding/removing the visible ones, merge, delete, and which spheres
// faults let through (fault.filter). Later analysis plugs in through PanelExtensions.
#include "core/session/commands.hpp"
#include "core/session/fault_surface_request.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/viewport/fault_edit.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace faultline::ui {

namespace {

constexpr float kPalette[][3] = {
    {0.90f, 0.30f, 0.20f}, {0.20f, 0.55f, 0.90f}, {0.95f, 0.70f, 0.10f}, {0.40f, 0.75f, 0.30f},
    {0.65f, 0.35f, 0.80f}, {0.10f, 0.75f, 0.75f}, {0.95f, 0.45f, 0.65f}, {0.60f, 0.45f, 0.25f},
    {0.55f, 0.85f, 0.10f}, {0.35f, 0.35f, 0.95f}, {0.20f, 0.20f, 0.20f}, {0.85f, 0.85f, 0.85f}};

// A "from": "visible" command, and deleting the faults whose every sphere is visible (it takes
// them all), in one step. The op reads the current frame's visible spheres: the main view's are
// those when it shows that frame; otherwise the command goes alone.
core::Json withEmptiedByVisible(PanelContext& wb, core::Json cmd, const std::string& into) {
    const ViewDisplay* main = wb.mainDisplay();
    if (!main || !main->frame || !main->visibility || main->shownFrame != wb.state().frame)
        return cmd;
    return withEmptiedRemoved(wb.state(), std::move(cmd),
                              core::visibleSpheresFault(*main->frame, *main->visibility).ids, into);
}

class FaultsPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kFaults; }
    const char* title() const override { return "Faults"; }

    void draw(PanelContext& wb) override {
        const core::SessionState& s = wb.state();
        const ViewDisplay* main = wb.mainDisplay();
        const bool haveVisible =
            main && main->frame && main->visibility && main->visibility->visibleCount > 0;
        auto& selected = wb.selection().faults;

        ImGui::BeginDisabled(!haveVisible);
        if (ImGui::Button("New from visible")) {
            const std::string name = nextFaultName(s);
            wb.emit(withEmptiedByVisible(wb, core::cmd::faultCreateVisible(name), name),
                    [&wb, name] { wb.selection().faults = {name}; });
        }
        wb.mark("faults.create");
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("A new fault whose members are the spheres visible now (%zu)",
                              haveVisible ? main->visibility->visibleCount : std::size_t(0));
        flowSameLine(buttonWidth("Merge"));
        ImGui::BeginDisabled(selected.size() < 2);
        if (ImGui::Button("Merge")) {
            std::vector<std::string> names;
            for (const auto& f : s.faults) // in table order; the first keeps its name
                if (selected.count(f.name))
                    names.push_back(f.name);
            const std::string into = names.front();
            wb.emit(core::cmd::faultMerge(names, into),
                    [&wb, into] { wb.selection().faults = {into}; });
        }
        ImGui::EndDisabled();
        flowSameLine(buttonWidth("Split"));
        ImGui::BeginDisabled(selected.size() != 1);
        if (ImGui::Button("Split")) {
            const std::string name = *selected.begin();
            const bool hadSurface = wb.state().surface(name) != nullptr;
            wb.emit(core::cmd::faultSplit(name), [&wb, name, hadSurface] {
                wb.selection().faults = {name + ".1"};
                int pieces = 0;
                while (wb.state().fault(name + "." + std::to_string(pieces + 1)))
                    ++pieces;
                wb.info("Split " + name + " into " + std::to_string(pieces) +
                        " faults; pieces under " + std::to_string(core::kDefaultCandidateMinSize) +
                        " spheres stay with " + name + ".1" +
                        (hadSurface ? "; each keeps the surface settings" : ""));
            });
        }
        wb.mark("faults.split");
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip(
                "Split the selected fault into the faults it holds (name.1 the largest, in its "
                "colour; name.2, ...); pieces under %d spheres stay with name.1, and every "
                "piece keeps its surface settings",
                static_cast<int>(core::kDefaultCandidateMinSize));
        flowSameLine(buttonWidth("Delete"));
        ImGui::BeginDisabled(selected.empty());
        if (ImGui::Button("Delete")) {
            std::vector<core::Json> batch;
            for (const auto& n : selected)
                batch.push_back(core::cmd::faultDelete(n));
            wb.emit(core::cmd::batch(std::move(batch)));
        }
        wb.mark("faults.delete");
        ImGui::EndDisabled();

        // Which spheres faults let through.
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Show");
        flowSameLine(ImGui::GetFontSize() * 7); // a narrow panel: the menu under its label
        const auto& filter = s.faultFilter;
        std::string current = filter.mode == core::FaultFilter::Mode::All ? "all spheres"
                              : filter.mode == core::FaultFilter::Mode::Labelled
                                  ? "spheres in visible faults"
                                  : "only " + filter.fault;
        ImGui::SetNextItemWidth(-1);
        if (ImGui::BeginCombo("##filter", current.c_str())) {
            if (ImGui::Selectable("all spheres", filter.mode == core::FaultFilter::Mode::All))
                wb.emit(core::cmd::faultFilter({core::FaultFilter::Mode::All, {}}));
            wb.mark("faults.filter.all");
            if (ImGui::Selectable("spheres in visible faults",
                                  filter.mode == core::FaultFilter::Mode::Labelled))
                wb.emit(core::cmd::faultFilter({core::FaultFilter::Mode::Labelled, {}}));
            wb.mark("faults.filter.labelled");
            for (const auto& f : s.faults) {
                if (ImGui::Selectable(("only " + f.name).c_str(),
                                      filter.mode == core::FaultFilter::Mode::Only &&
                                          filter.fault == f.name))
                    wb.emit(core::cmd::faultFilter({core::FaultFilter::Mode::Only, f.name}));
                wb.mark("faults.filter.only." + f.name);
            }
            ImGui::EndCombo();
        }
        wb.mark("faults.filter");

        if (s.faults.empty()) {
            ImGui::Spacing();
            ImGui::TextWrapped(
                "No faults yet. Narrow the visible spheres with thresholds (for example on "
                "broken bonds or strain) and boxes, then press \"New from visible\".");
        } else {
            drawTable(wb);
            if (selected.size() == 1)
                if (const core::Fault* f = s.fault(*selected.begin()))
                    drawDetails(wb, *f, haveVisible);
        }
        for (const auto& section : wb.extensions().faultSections) {
            ImGui::Spacing();
            const bool open = collapsingHeader(
                section.title, section.defaultOpen ? ImGuiTreeNodeFlags_DefaultOpen : 0);
            wb.mark("faults.section." + section.title);
            if (open)
                section.draw(wb);
        }
    }

  private:
    void drawTable(PanelContext& wb) {
        const core::SessionState& s = wb.state();
        auto& selected = wb.selection().faults;
        const auto& extra = wb.extensions().faultColumns;
        const int columns = 4 + static_cast<int>(extra.size());
        const float rowH = ImGui::GetFrameHeightWithSpacing();
        const float tableH =
            std::min(rowH * (static_cast<float>(s.faults.size()) + 1.2f), rowH * 9.0f);
        if (!beginScrollingTable("##faults", columns,
                                 ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersOuter |
                                     ImGuiTableFlags_ScrollY | ImGuiTableFlags_Resizable,
                                 tableH))
            return;
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed,
                                ImGui::GetFrameHeight() * 2.2f);
        ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthStretch, 2.0f);
        ImGui::TableSetupColumn("spheres", ImGuiTableColumnFlags_WidthFixed,
                                ImGui::CalcTextSize("0000000").x);
        ImGui::TableSetupColumn("notes", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        for (const auto& c : extra)
            ImGui::TableSetupColumn(c.title.c_str(), ImGuiTableColumnFlags_WidthFixed,
                                    ImGui::CalcTextSize("000000").x);
        ImGui::TableHeadersRow();
        for (const core::Fault& f : s.faults) {
            ImGui::PushID(f.name.c_str());
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            bool visible = f.visible;
            if (ImGui::Checkbox("##visible", &visible))
                wb.emit(core::cmd::FaultSet(f.name).visible(visible));
            wb.mark("faults.visible." + f.name);
            ImGui::SameLine(0, 4);
            drawSwatch(wb, f);
            ImGui::TableNextColumn();
            ImGui::AlignTextToFramePadding();
            const std::string shown = elided(f.name, ImGui::GetContentRegionAvail().x);
            if (m_renaming == f.name) // double-clicked: the name cell edits it in place
                drawRename(wb, f);
            else
                drawNameCell(wb, f, shown, selected);
            ImGui::TableNextColumn();
            ImGui::Text("%zu", f.ids.size());
            ImGui::TableNextColumn();
            const std::string notes = elided(f.notes, ImGui::GetContentRegionAvail().x);
            ImGui::TextDisabled("%s", notes.c_str());
            if (!f.notes.empty() && ImGui::IsItemHovered())
                ImGui::SetTooltip("%s", f.notes.c_str());
            for (const auto& c : extra) {
                ImGui::TableNextColumn();
                c.cell(wb, f);
            }
            ImGui::PopID();
        }
        ImGui::EndTable();
    }

    // The name cell: selects (Ctrl: adds to the selection); a double-click renames in place.
    void drawNameCell(PanelContext& wb, const core::Fault& f, const std::string& shown,
                      std::set<std::string>& selected) {
        const bool isSelected = selected.count(f.name) > 0;
        if (ImGui::Selectable((shown + "##row").c_str(), isSelected,
                              ImGuiSelectableFlags_SpanAllColumns |
                                  ImGuiSelectableFlags_AllowItemOverlap)) {
            if (ImGui::GetIO().KeyCtrl) {
                if (isSelected)
                    selected.erase(f.name);
                else
                    selected.insert(f.name);
            } else {
                selected = {f.name};
            }
        }
        if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0)) {
            m_renaming = f.name;
            m_renameText = f.name;
            m_renameFocus = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s\ndouble-click to rename", f.name.c_str());
        wb.mark("faults.row." + f.name);
    }

    // The name being edited: Enter renames (fault.set), Escape or leaving the field keeps it.
    void drawRename(PanelContext& wb, const core::Fault& f) {
        if (m_renameFocus) {
            ImGui::SetKeyboardFocusHere();
            m_renameFocus = false;
        }
        ImGui::SetNextItemWidth(-1);
        const bool enter = ImGui::InputText("##rename", &m_renameText,
                                            ImGuiInputTextFlags_EnterReturnsTrue |
                                                ImGuiInputTextFlags_AutoSelectAll);
        wb.mark("faults.rename." + f.name);
        if (enter && !m_renameText.empty() && m_renameText != f.name) {
            const std::string next = m_renameText;
            wb.emit(core::cmd::FaultSet(f.name).rename(next),
                    [&wb, next] { wb.selection().faults = {next}; });
        }
        if (enter || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)) ||
            ImGui::IsItemDeactivated())
            m_renaming.clear();
    }

    // A colour square; clicking opens a palette and a picker (committed when the popup closes).
    void drawSwatch(PanelContext& wb, const core::Fault& f) {
        const ImVec4 c(f.color[0], f.color[1], f.color[2], 1.0f);
        if (ImGui::ColorButton("##color", c, ImGuiColorEditFlags_NoTooltip,
                               ImVec2(ImGui::GetFrameHeight(), ImGui::GetFrameHeight()))) {
            m_colorFault = f.name;
            std::copy(f.color.begin(), f.color.end(), m_color);
            ImGui::OpenPopup("##colorpopup");
        }
        if (ImGui::BeginPopup("##colorpopup")) {
            int k = 0;
            for (const auto& p : kPalette) {
                if (k++ % 6)
                    ImGui::SameLine();
                ImGui::PushID(k);
                if (ImGui::ColorButton("##p", ImVec4(p[0], p[1], p[2], 1))) {
                    std::copy(p, p + 3, m_color);
                    ImGui::CloseCurrentPopup();
                }
                ImGui::PopID();
            }
            ImGui::ColorPicker3("##picker", m_color,
                                ImGuiColorEditFlags_NoSidePreview |
                                    ImGuiColorEditFlags_NoSmallPreview);
            ImGui::EndPopup();
        } else if (m_colorFault == f.name) {
            if (m_color[0] != f.color[0] || m_color[1] != f.color[1] || m_color[2] != f.color[2])
                wb.emit(core::cmd::FaultSet(f.name).color({m_color[0], m_color[1], m_color[2]}));
            m_colorFault.clear();
        }
    }

    void drawDetails(PanelContext& wb, const core::Fault& f, bool haveVisible) {
        ImGui::Spacing();
        sectionHeader("Fault \"" + f.name + "\"");
        if (m_editFor != f.name) {
            m_editFor = f.name;
            m_name = f.name;
            m_notes = f.notes;
        }
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Name");
        ImGui::SameLine(ImGui::GetFontSize() * 4);
        ImGui::SetNextItemWidth(-1);
        ImGui::InputText("##name", &m_name);
        if (ImGui::IsItemDeactivatedAfterEdit() && !m_name.empty() && m_name != f.name) {
            const std::string next = m_name;
            wb.emit(core::cmd::FaultSet(f.name).rename(next),
                    [&wb, next] { wb.selection().faults = {next}; });
        }
        wb.mark("faults.name");
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Notes");
        ImGui::SameLine(ImGui::GetFontSize() * 4);
        ImGui::InputTextMultiline("##notes", &m_notes,
                                  ImVec2(-1, ImGui::GetTextLineHeight() * 3.2f));
        if (ImGui::IsItemDeactivatedAfterEdit() && m_notes != f.notes)
            wb.emit(core::cmd::FaultSet(f.name).notes(m_notes));
        wb.mark("faults.notes");
        ImGui::BeginDisabled(!haveVisible);
        // A narrow panel shortens the labels (the whole on hover) rather than cut them.
        const bool shortLabels =
            ImGui::GetContentRegionAvail().x < buttonWidth("Remove the visible spheres");
        if (ImGui::Button(shortLabels ? "Add visible###add" : "Add the visible spheres###add"))
            wb.emit(withEmptiedByVisible(wb, core::cmd::faultAddVisible(f.name), f.name));
        if (shortLabels && ImGui::IsItemHovered())
            ImGui::SetTooltip("Add the visible spheres to %s", f.name.c_str());
        flowSameLine(buttonWidth(shortLabels ? "Remove visible" : "Remove the visible spheres"));
        if (ImGui::Button(shortLabels ? "Remove visible###remove"
                                      : "Remove the visible spheres###remove")) {
            const ViewDisplay* main = wb.mainDisplay();
            std::vector<std::int64_t> ids;
            for (std::size_t row = 0; row < main->visibility->mask.size(); ++row)
                if (main->visibility->mask[row] &&
                    std::binary_search(f.ids.begin(), f.ids.end(), main->frame->ids[row]))
                    ids.push_back(main->frame->ids[row]);
            if (!ids.empty())
                wb.emit(core::cmd::faultRemove(f.name, ids));
        }
        if (shortLabels && ImGui::IsItemHovered())
            ImGui::SetTooltip("Remove the visible spheres from %s", f.name.c_str());
        ImGui::EndDisabled();
    }

    std::string m_colorFault;
    float m_color[3] = {1, 0.5f, 0};
    std::string m_editFor, m_name, m_notes;
    std::string m_renaming, m_renameText; // the fault renamed in place (double-click)
    bool m_renameFocus = false;
};

} // namespace

std::unique_ptr<Panel> makeFaultsPanel() { return std::make_unique<FaultsPanel>(); }

} // namespace faultline::ui
