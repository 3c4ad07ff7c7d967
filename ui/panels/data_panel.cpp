// Data panel: the files open, their frames, the current frame's columns with ranges, memory.
#include "core/io/frame_source.hpp"
#include "core/model/packing.hpp"
#include "core/session/commands.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/panels/strain_section.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace faultline::ui {

namespace {

class DataPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kData; }
    const char* title() const override { return "Data"; }

    void draw(PanelContext& wb) override {
        auto ds = wb.dataset();
        if (ImGui::Button("Open data..."))
            wb.fileDialog().open("Open data (a file, or a pattern such as dump.*.gz)",
                                 FileDialog::Mode::Open, "open-data", {}, "");
        wb.mark("data.open");
        flowSameLine(buttonWidth("Close"));
        ImGui::BeginDisabled(!ds);
        if (ImGui::Button("Close"))
            wb.emit(core::cmd::dataClose());
        wb.mark("data.close");
        ImGui::EndDisabled();
        if (!ds) {
            ImGui::Spacing();
            ImGui::TextWrapped(
                "No data is open. Open a LAMMPS or LIGGGHTS dump (also .gz, a numbered series "
                "as a pattern, or per-processor files with %%), a VTK file or a CSV table, or "
                "drop a file onto the window.");
            return;
        }
        ImGui::Spacing();
        if (collapsingHeader("Files", ImGuiTreeNodeFlags_DefaultOpen)) {
            const auto files = ds->files();
            const auto& loc = ds->location(0);
            hint("%zu file%s, %s", files.size(), files.size() == 1 ? "" : "s",
                 std::string(core::formatName(loc.format)).c_str());
            const std::size_t shown = std::min<std::size_t>(files.size(), 6);
            for (std::size_t k = 0; k < shown; ++k) {
                const std::string name = std::filesystem::path(files[k]).filename().string();
                ImGui::Bullet();
                textElided(name); // the whole path on hover
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%s", files[k].c_str());
            }
            if (files.size() > shown)
                ImGui::TextDisabled("... and %zu more", files.size() - shown);
        }
        const ViewDisplay* main = wb.mainDisplay();
        if (collapsingHeader("Frames", ImGuiTreeNodeFlags_DefaultOpen)) {
            const std::size_t f = wb.displayFrame();
            keyValue("frames", std::to_string(ds->frameCount()));
            for (const auto& note : ds->notes()) // a file cut short: its last frame left out
                ImGui::TextWrapped("%s", note.c_str());
            keyValue("current", std::to_string(f) + "  (timestep " +
                                    std::to_string(ds->location(f).timestep) + ")");
            if (main && main->frame) {
                const core::Frame& fr = *main->frame;
                keyValue("spheres", std::to_string(fr.size()));
                if (main->visibility)
                    keyValue("visible", std::to_string(main->visibility->visibleCount));
                const ModelBounds& b = main->bounds;
                keyValue("extent", numberText(b.hi[0] - b.lo[0]) + " x " +
                                       numberText(b.hi[1] - b.lo[1]) + " x " +
                                       numberText(b.hi[2] - b.lo[2]));
                if (fr.radiusIsDefault)
                    ImGui::TextDisabled("no radius column: radius %.2g assumed",
                                        core::kDefaultRadius);
                if (fr.idsAreRowNumbers)
                    ImGui::TextDisabled("no id column: row numbers are the ids");
                // Radii in another unit than the centres (millimetres beside metres) would draw
                // one blob, slowly, and give strain from motion no neighbourhood: the views draw
                // them scaled down (core::radiusDrawScale), and this says so, once per frame.
                if (m_radiiFor.lock() != main->frame) {
                    m_radiiFor = main->frame;
                    m_radiiNote = core::radiiUnitNote(fr);
                    if (const double scale = core::radiusDrawScale(fr); scale != 1.0)
                        m_radiiNote += " The views draw them " +
                                       std::to_string(std::lround(1 / scale)) + " times smaller.";
                }
                if (!m_radiiNote.empty()) {
                    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.45f, 0.05f, 1));
                    ImGui::TextWrapped("%s", m_radiiNote.c_str());
                    ImGui::PopStyleColor();
                    wb.mark("data.radii_note");
                }
            }
        }
        if (main && main->frame && collapsingHeader("Columns", ImGuiTreeNodeFlags_DefaultOpen)) {
            // A narrow panel keeps the names and gives the type and range on hover.
            const bool wide = ImGui::GetContentRegionAvail().x >= ImGui::GetFontSize() * 16;
            if (ImGui::BeginTable("##columns", wide ? 4 : 1,
                                  ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                      ImGuiTableFlags_SizingStretchProp)) {
                ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthStretch, 1.4f);
                if (wide) {
                    ImGui::TableSetupColumn("type", ImGuiTableColumnFlags_WidthStretch, 0.6f);
                    ImGui::TableSetupColumn("min", ImGuiTableColumnFlags_WidthStretch, 1.0f);
                    ImGui::TableSetupColumn("max", ImGuiTableColumnFlags_WidthStretch, 1.0f);
                }
                ImGui::TableHeadersRow();
                for (const auto& [name, col] : wb.columns().of(main->frame)) {
                    const VariableInfo* info = &col;
                    ImGui::TableNextRow();
                    ImGui::TableNextColumn();
                    if (!textElided(name) && !wide && ImGui::IsItemHovered())
                        ImGui::SetTooltip(
                            "%s  %s  %s .. %s", name.c_str(), info->integer ? "int" : "float",
                            numberText(info->min).c_str(), numberText(info->max).c_str());
                    if (!wide)
                        continue;
                    ImGui::TableNextColumn();
                    ImGui::TextDisabled("%s", info->integer ? "int" : "float");
                    ImGui::TableNextColumn();
                    ImGui::TextUnformatted(numberText(info->min).c_str());
                    ImGui::TableNextColumn();
                    ImGui::TextUnformatted(numberText(info->max).c_str());
                }
                ImGui::EndTable();
            }
        }
        if (collapsingHeader("Strain from motion", ImGuiTreeNodeFlags_DefaultOpen))
            m_strain.draw(wb);
        if (collapsingHeader("Memory", ImGuiTreeNodeFlags_DefaultOpen)) {
            if (main && main->frame)
                keyValue("this frame", bytesText(main->frame->memoryBytes()));
            keyValue("frames cached",
                     bytesText(ds->cachedBytes()) + " of " + bytesText(ds->cacheBudget()));
            // The budget of frames kept in memory (older ones are dropped, prefetch stays inside).
            const bool beside = ImGui::GetContentRegionAvail().x >= ImGui::GetFontSize() * 15;
            ImGui::TextDisabled("budget");
            if (beside) // a narrow panel puts the field under its name
                ImGui::SameLine(ImGui::GetFontSize() * 8);
            if (!ImGui::IsItemActive() && !m_editingBudget)
                m_budgetMb = static_cast<int>(wb.frameMemoryBudget() >> 20);
            ImGui::SetNextItemWidth(std::clamp(ImGui::GetContentRegionAvail().x -
                                                   ImGui::CalcTextSize("MB").x -
                                                   ImGui::GetStyle().ItemInnerSpacing.x,
                                               ImGui::GetFontSize() * 3, ImGui::GetFontSize() * 7));
            ImGui::InputInt("MB##budget", &m_budgetMb, 256, 1024);
            m_editingBudget = ImGui::IsItemActive();
            wb.mark("data.budget");
            if (ImGui::IsItemDeactivatedAfterEdit() ||
                (ImGui::IsItemEdited() && !ImGui::IsItemActive()))
                wb.setFrameMemoryBudget(static_cast<std::size_t>(std::max(64, m_budgetMb)) << 20);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "Memory for frames kept while scrubbing (default: a quarter of RAM)");
            flowSameLine(buttonWidth("default"));
            if (ImGui::SmallButton("default"))
                wb.setFrameMemoryBudget(0);
        }
    }

  private:
    StrainSection m_strain;
    int m_budgetMb = 0;
    bool m_editingBudget = false;
    // The note on radii far larger than the centres' spacing, for the frame it was made for.
    std::weak_ptr<const core::Frame> m_radiiFor;
    std::string m_radiiNote;

    // "key   value", the value wrapped at the panel's edge in its column (issue 41: a narrow
    // panel cut "39 (timestep 3..." and the extent).
    // In a panel too narrow for the two columns the value goes under its key.
    static void keyValue(const char* key, const std::string& value) {
        const float column = ImGui::GetFontSize() * 8;
        const bool beside = ImGui::GetContentRegionAvail().x >= column + ImGui::GetFontSize() * 5;
        ImGui::TextDisabled("%s", key);
        if (beside)
            ImGui::SameLine(column);
        else
            ImGui::Indent();
        ImGui::BeginGroup();
        textWrappedAtSpaces(value);
        ImGui::EndGroup();
        if (!beside)
            ImGui::Unindent();
    }
};

} // namespace

std::unique_ptr<Panel> makeDataPanel() { return std::make_unique<DataPanel>(); }

} // namespace faultline::ui
