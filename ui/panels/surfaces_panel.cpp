// Surfaces panel: a metaball surface per fault, and one of the visible spheres (paper eq. 1 /
// Algorithm 1): show or hide it, its kernel, voxel size, iso-value and opacity, the state of its
// background build, and exports to OpenVDB and glTF. Settings are surface.set commands; builds
// run in the workbench's SurfaceStore.
//
// Index of this file:
// [SECTION] Helpers
// [SECTION] The panel
// [SECTION] The table of surfaces
// [SECTION] A surface's settings and exports
// [SECTION] A surface's colour
#include "core/session/commands.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include "core/color/colormap.hpp"
#include "core/session/fault_surface_request.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/widgets/number_field.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace faultline::ui {

namespace {

const char* kKernels[] = {"inverse", "inverse-square", "compact"};

//-----------------------------------------------------------------------------
// [SECTION] Helpers
//-----------------------------------------------------------------------------

// How the panel names a surface source.
std::string sourceLabel(const std::string& name) {
    return core::isVisibleSpheres(name) ? "visible spheres" : name;
}

std::string statusText(const SurfaceStatus& st) {
    using State = SurfaceStatus::State;
    switch (st.state) {
    case State::Waiting:
        return "waiting";
    case State::Building:
        return st.progress >= 0 ? "building " + std::to_string(int(st.progress * 100)) + "%"
                                : "building";
    case State::Ready: {
        char text[48];
        const double n = static_cast<double>(st.triangles);
        if (n >= 1e6)
            std::snprintf(text, sizeof text, "%.3gM triangles", n / 1e6);
        else if (n >= 1e4)
            std::snprintf(text, sizeof text, "%.3gk triangles", n / 1e3);
        else
            std::snprintf(text, sizeof text, "%zu triangles", st.triangles);
        return text;
    }
    case State::Failed:
        return "failed";
    case State::NotFormed:
        return "not formed yet";
    case State::None:
        break;
    }
    return "";
}

//-----------------------------------------------------------------------------
// [SECTION] The panel
//-----------------------------------------------------------------------------

class SurfacesPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kSurfaces; }
    const char* title() const override { return "Surfaces"; }

    void draw(PanelContext& wb) override {
        const core::SessionState& s = wb.state();
        const ViewDisplay* main = wb.mainDisplay();
        const std::size_t frame = main ? main->shownFrame : 0;
        drawTable(wb, s, frame);
        if (s.faults.empty())
            ImGui::TextWrapped(
                "No faults yet. Name one in the Faults panel (from the visible spheres or a "
                "candidate) for a surface of its own.");
        const std::string current = currentFault(wb, s);
        if (current.empty())
            return;
        ImGui::Separator();
        drawSettings(wb, s, current, frame);
    }

  private:
    std::shared_ptr<Job> m_wrapping; // finding an iso-value for `cmd` (sums every member)
    std::string m_fault;             // whose settings are shown
    std::string m_selected;          // the fault last picked in the Faults panel
    float m_iso = 1.0f, m_opacity = 0.8f;
    double m_voxel = 0.0;
    std::string m_editing; // fault whose edit fields were loaded
    double m_reach = 0.0;
    bool m_gltfGlyphs = false; // glTF exports carry the spheres as instanced glyphs too
    std::string m_editingReach;
    std::array<float, 3> m_colour{1, 1, 1}; // the own colour being edited
    std::string m_editingColour;

    // Emits `cmd` (a surface.set) with the iso-value that wraps the fault's spheres in the shown
    // frame, found in the background (about 600 field sums over all of them). Without one (no
    // member in the frame) `cmd` goes as it is, unless it asks for nothing else.
    void emitWithWrappingIso(PanelContext& wb, const std::string& source,
                             const core::SurfaceSettings& settings, core::cmd::SurfaceSet cmd,
                             bool onlyIso = false) {
        const ViewDisplay* main = wb.mainDisplay();
        const core::Fault* found =
            main ? wb.surfaces().sourceOf(wb.state(), source, main->frame, main->visibility)
                 : nullptr;
        if (!main || !main->frame || !found) {
            if (!onlyIso)
                wb.emit(cmd);
            return;
        }
        const core::Fault fault = *found;
        if (m_wrapping && !m_wrapping->finished())
            m_wrapping->cancel();
        m_wrapping = wb.jobs().start(
            "Finding the iso-value that wraps " + fault.name,
            [&wb, frame = main->frame, fault, settings, cmd,
             onlyIso](JobControl&) mutable -> std::function<void()> {
                if (const auto iso = core::faultWrappingIso(*frame, fault, settings))
                    cmd.iso(*iso);
                else if (onlyIso)
                    return {};
                return [&wb, cmd] { wb.emit(cmd); };
            },
            [&wb](const std::string& why) { wb.error("Cannot find an iso-value: " + why); },
            wb.now());
    }

    std::string currentFault(PanelContext& wb, const core::SessionState& s) {
        // A fault picked in the Faults panel shows its settings (once: a click here wins).
        const std::string picked =
            wb.selection().faults.size() == 1 ? *wb.selection().faults.begin() : std::string();
        if (picked != m_selected) {
            m_selected = picked;
            if (s.fault(picked))
                m_fault = picked;
        }
        if (!s.hasSurfaceSource(m_fault))
            m_fault = !s.surfaces.empty() ? s.surfaces.front().fault
                      : !s.faults.empty() ? s.faults.front().name
                                          : std::string(core::kVisibleSpheres);
        return m_fault;
    }

    //-----------------------------------------------------------------------------
    // [SECTION] The table of surfaces
    //-----------------------------------------------------------------------------

    void drawTable(PanelContext& wb, const core::SessionState& s, std::size_t frame) {
        const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH |
                                      ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingStretchProp;
        const float rows = static_cast<float>(std::min<std::size_t>(s.faults.size() + 1, 6) + 1);
        if (!beginScrollingTable("##surfaces", 3, flags, rows * ImGui::GetFrameHeightWithSpacing()))
            return;
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableSetupColumn("shown", ImGuiTableColumnFlags_WidthFixed);
        ImGui::TableSetupColumn("of", ImGuiTableColumnFlags_WidthStretch, 1.2f);
        ImGui::TableSetupColumn("surface", ImGuiTableColumnFlags_WidthStretch, 1.0f);
        ImGui::TableHeadersRow();
        for (const auto& f : s.faults)
            drawRow(wb, s, frame, f.name, f.color);
        drawRow(wb, s, frame, std::string(core::kVisibleSpheres), core::kVisibleSpheresColor);
        ImGui::EndTable();
    }

    void drawRow(PanelContext& wb, const core::SessionState& s, std::size_t frame,
                 const std::string& name, const std::array<float, 3>& color) {
        const bool visibleSpheres = core::isVisibleSpheres(name);
        ImGui::PushID(name.c_str());
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        const core::SurfaceSettings* st = s.surface(name);
        bool shown = st && st->visible;
        if (ImGui::Checkbox("##shown", &shown)) {
            if (shown)
                m_fault = name; // the settings below are the surface just ticked
            core::cmd::SurfaceSet cmd(name);
            cmd.visible(shown);
            // A new surface starts at the iso that wraps its spheres.
            if (!st && shown)
                emitWithWrappingIso(wb, name, core::SurfaceSettings{}, cmd);
            else
                wb.emit(cmd);
        }
        wb.mark(visibleSpheres ? std::string("surfaces.show.visible") : "surfaces.show." + name);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(visibleSpheres
                                  ? "Show the metaball surface through the visible spheres (it "
                                    "follows thresholds, boxes and time)"
                                  : "Show the metaball surface through this fault's spheres");
        ImGui::TableNextColumn();
        ImVec4 colour(color[0], color[1], color[2], 1.0f);
        if (st && st->colorBy.empty() && st->color) // its own colour
            colour = ImVec4(float((*st->color)[0]), float((*st->color)[1]), float((*st->color)[2]),
                            1.0f);
        ImGui::ColorButton("##c", colour,
                           ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoPicker,
                           ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
        ImGui::SameLine();
        const std::string label = sourceLabel(name);
        const std::string shownLabel = elided(label, ImGui::GetContentRegionAvail().x);
        if (ImGui::Selectable((shownLabel + "##pick").c_str(), m_fault == name,
                              ImGuiSelectableFlags_SpanAllColumns))
            m_fault = name;
        if (shownLabel != label && ImGui::IsItemHovered())
            ImGui::SetTooltip("%s", label.c_str());
        if (visibleSpheres)
            wb.mark("surfaces.pick.visible");
        ImGui::TableNextColumn();
        if (st && st->visible) {
            const SurfaceStatus status = statusOf(wb, s, name, frame);
            if (status.state == SurfaceStatus::State::Building && status.progress >= 0) {
                ImGui::ProgressBar(status.progress, ImVec2(-1, 0), statusText(status).c_str());
            } else if (status.state == SurfaceStatus::State::Failed) {
                ImGui::TextColored(ImVec4(0.75f, 0.15f, 0.1f, 1), "failed");
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%s", status.error.c_str());
            } else {
                const bool cut = textElided(statusText(status));
                if (status.state == SurfaceStatus::State::Ready && !cut && ImGui::IsItemHovered())
                    ImGui::SetTooltip("%zu spheres, built in %.2f s", status.spheres,
                                      status.seconds);
            }
        } else {
            ImGui::TextDisabled(st ? "hidden" : "-");
        }
        ImGui::PopID();
    }

    static SurfaceStatus statusOf(PanelContext& wb, const core::SessionState& s,
                                  const std::string& name, std::size_t frame) {
        const ViewDisplay* main = wb.mainDisplay();
        return wb.surfaces().status(s, name, frame, main ? main->frame : nullptr,
                                    main ? main->visibility : nullptr);
    }

    //-----------------------------------------------------------------------------
    // [SECTION] A surface's settings and exports
    //-----------------------------------------------------------------------------

    void drawSettings(PanelContext& wb, const core::SessionState& s, const std::string& fault,
                      std::size_t frame) {
        core::SurfaceSettings st;
        st.fault = fault;
        if (const core::SurfaceSettings* saved = s.surface(fault))
            st = *saved;
        if (m_editing != fault || !ImGui::IsAnyItemActive()) {
            m_iso = static_cast<float>(st.iso);
            m_opacity = static_cast<float>(st.opacity);
            m_voxel = st.voxel;
            m_editing = fault;
        }
        textElided("Surface of " + sourceLabel(fault));
        // Fields 170 px wide where the panel allows, leaving room for their labels.
        const float w = std::max(
            60 * wb.scale(), std::min(170 * wb.scale(), ImGui::GetContentRegionAvail().x -
                                                            ImGui::CalcTextSize("opacity").x -
                                                            ImGui::GetStyle().ItemInnerSpacing.x));
        ImGui::SetNextItemWidth(w);
        const std::string current(core::kernelName(st.kernel));
        if (ImGui::BeginCombo("kernel", current.c_str())) {
            for (const char* k : kKernels) {
                const bool picked = ImGui::Selectable(k, current == k);
                wb.mark(std::string("surfaces.kernel.") + k);
                if (picked && current != k) {
                    // The kernels' fields differ by orders of magnitude: a new kernel comes with
                    // the iso-value that wraps the spheres with it.
                    core::SurfaceSettings next = st;
                    next.kernel = *core::parseKernel(k);
                    emitWithWrappingIso(wb, fault, next,
                                        core::cmd::SurfaceSet(fault).kernel(next.kernel));
                }
            }
            ImGui::EndCombo();
        }
        wb.mark("surfaces.kernel");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("inverse: sum r/d (Algorithm 1); inverse-square: sum r/d^2 (eq. 1);\n"
                              "compact: Wyvill's kernel, zero beyond 3 radii (fastest).\n"
                              "A new kernel takes the iso-value that wraps the spheres with it.");
        if (numberField("voxel", &m_voxel, "%.4g", w, "auto", 0.0) && m_voxel >= 0 &&
            m_voxel != st.voxel)
            wb.emit(core::cmd::SurfaceSet(fault).voxel(m_voxel));
        wb.mark("surfaces.voxel");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Voxel edge in world units; 0 = the mean radius / 3. Smaller is finer and slower.");
        const SurfaceStatus status = statusOf(wb, s, fault, frame);
        // The slider spans the iso-values worth trying for this fault and kernel (from the built
        // field: a loose hull at the left, the surface shrunk into the spheres at the right), on
        // a log scale; before a build, a decade either side of the setting. The value stands in
        // its own field beside the slider (one click to type), so the thumb never hides it.
        const float anchor = static_cast<float>(st.iso);
        float low = anchor / 10.0f, high = anchor * 10.0f;
        if (status.isoHigh > status.isoLow && status.isoLow > 0.0f) {
            low = std::min(status.isoLow, anchor);
            high = std::max(status.isoHigh, anchor);
        }
        const float valueW = 64 * wb.scale();
        ImGui::SetNextItemWidth(
            std::max(w - valueW - ImGui::GetStyle().ItemSpacing.x, 30 * wb.scale()));
        ImGui::SliderFloat("##iso", &m_iso, low, high, "",
                           ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoInput);
        if (ImGui::IsItemDeactivatedAfterEdit() && m_iso > 0)
            wb.emit(core::cmd::SurfaceSet(fault).iso(m_iso));
        wb.mark("surfaces.iso");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The field value the surface passes through (%.3g .. %.3g here: "
                              "left a loose hull, right the spheres alone); a new value re-meshes "
                              "the cached field.",
                              low, high);
        ImGui::SameLine();
        double isoValue = m_iso;
        if (numberField("iso", &isoValue, "%.4g", valueW) && isoValue > 0) {
            m_iso = static_cast<float>(isoValue);
            wb.emit(core::cmd::SurfaceSet(fault).iso(isoValue));
        }
        wb.mark("surfaces.iso_value");
        flowSameLine(buttonWidth("Wrap"));
        if (ImGui::Button("Wrap"))
            emitWithWrappingIso(wb, fault, st, core::cmd::SurfaceSet(fault), true);
        wb.mark("surfaces.wrap");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The iso-value whose surface wraps these spheres about half a "
                              "radius out (with this kernel)");
        ImGui::SetNextItemWidth(w);
        ImGui::SliderFloat("opacity", &m_opacity, 0.0f, 1.0f, "%.2f");
        if (ImGui::IsItemDeactivatedAfterEdit())
            wb.emit(core::cmd::SurfaceSet(fault).opacity(m_opacity));
        wb.mark("surfaces.opacity");

        drawColour(wb, s, st);

        if (status.state == SurfaceStatus::State::Failed)
            ImGui::TextWrapped("Cannot build: %s", status.error.c_str());
        else if (status.state == SurfaceStatus::State::NotFormed)
            ImGui::TextWrapped("Not formed in this frame: none of %s's spheres passes the "
                               "thresholds here, so no surface is drawn.",
                               sourceLabel(fault).c_str());
        else if (status.state == SurfaceStatus::State::Ready && status.triangles == 0) {
            // Say why nothing shows, and offer the way back.
            char why[160];
            if (status.fieldMax < status.iso)
                std::snprintf(why, sizeof why,
                              "No surface: iso %.3g is above the field's maximum, about %.3g.",
                              status.iso, status.fieldMax);
            else
                std::snprintf(why, sizeof why,
                              "No surface: iso %.3g lies below the field everywhere near these "
                              "spheres.",
                              status.iso);
            ImGui::TextWrapped("%s", why);
            if (ImGui::Button("Wrap the spheres"))
                emitWithWrappingIso(wb, fault, st, core::cmd::SurfaceSet(fault), true);
            wb.mark("surfaces.empty_wrap");
        } else if (status.state == SurfaceStatus::State::Ready) {
            const core::Fault* whole = s.fault(fault);
            if (whole && status.spheres < whole->ids.size()) // only part of it formed here
                hint("%zu of its %zu spheres pass the thresholds in this frame; %zu triangles, "
                     "%.2f s",
                     status.spheres, whole->ids.size(), status.triangles, status.seconds);
            else
                hint("%zu spheres, %zu triangles, %.2f s", status.spheres, status.triangles,
                     status.seconds);
        }

        const bool exists = s.surface(fault) != nullptr;
        ImGui::BeginDisabled(!wb.dataset());
        if (ImGui::Button("Export VDB..."))
            wb.fileDialog().open(
                "Export the density and colour grids of the " +
                    (core::isVisibleSpheres(fault) ? "visible spheres" : fault + " surface") +
                    " (OpenVDB)",
                FileDialog::Mode::Save, "export-vdb:" + fault, {".vdb"}, wb.exportFolder(),
                (core::isVisibleSpheres(fault) ? "visible" : fault) + ".vdb");
        ImGui::EndDisabled();
        // As File > Export: off until a surface is shown, rather than failing after the dialog
        // (walkthrough of issue 41).
        const bool anyShown = !s.shownSurfaces().empty();
        flowSameLine(buttonWidth("Export glTF..."));
        ImGui::BeginDisabled(!wb.dataset() || !anyShown);
        if (ImGui::Button("Export glTF..."))
            wb.fileDialog().open("Export the shown surfaces as glTF (one node per fault)",
                                 FileDialog::Mode::Save,
                                 m_gltfGlyphs ? "export-gltf+glyphs" : "export-gltf",
                                 {".glb", ".gltf"}, wb.exportFolder(), "faults.glb");
        wb.mark("surfaces.export_gltf");
        ImGui::EndDisabled();
        if (!anyShown && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("No surface is shown: tick one to export the shown surfaces");
        flowSameLine(buttonWidth("Remove"));
        ImGui::BeginDisabled(!exists);
        if (ImGui::Button("Remove"))
            wb.emit(core::cmd::surfaceRemove(fault));
        ImGui::EndDisabled();
        ImGui::Checkbox("glTF with the spheres", &m_gltfGlyphs);
        wb.mark("surfaces.gltf_glyphs");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The glTF export also carries each surface's spheres as instanced "
                              "glyphs, in the surface's colours");
    }

    //-----------------------------------------------------------------------------
    // [SECTION] A surface's colour
    //-----------------------------------------------------------------------------

    // Figure 4 colour: the spheres' colours (the fault's, or a variable through a colour map) and
    // the reach w within which a voxel takes a sphere's colour.
    void drawColour(PanelContext& wb, const core::SessionState& s,
                    const core::SurfaceSettings& st) {
        const ViewDisplay* main = wb.mainDisplay();
        // Fields 170 px wide where the panel allows, leaving room for their labels.
        const float w = std::max(
            60 * wb.scale(), std::min(170 * wb.scale(), ImGui::GetContentRegionAvail().x -
                                                            ImGui::CalcTextSize("opacity").x -
                                                            ImGui::GetStyle().ItemInnerSpacing.x));
        const std::string plain = core::isVisibleSpheres(st.fault) ? "one colour" : "fault colour";
        // Issue 41: a surface in its fault's colour is hard to see among the fault's spheres; a
        // colour of its own sets it apart.
        const char* custom = "own colour";
        const bool own = st.colorBy.empty() && st.color;
        ImGui::SetNextItemWidth(w);
        if (ImGui::BeginCombo("colour", own                  ? custom
                                        : st.colorBy.empty() ? plain.c_str()
                                                             : st.colorBy.c_str())) {
            if (ImGui::Selectable(plain.c_str(), st.colorBy.empty() && !own) &&
                (!st.colorBy.empty() || own))
                wb.emit(core::cmd::SurfaceSet(st.fault).colorBy("").color(std::nullopt));
            wb.mark("surfaces.color_by.plain");
            if (ImGui::Selectable(custom, own) && !own) {
                // Starts from the fault's colour turned to its complement: apart at once.
                std::array<double, 3> c{0.9, 0.9, 0.9};
                if (const core::Fault* f = s.fault(st.fault))
                    for (int k = 0; k < 3; ++k)
                        c[k] = 1.0 - f->color[k];
                wb.emit(core::cmd::SurfaceSet(st.fault).colorBy("").color(c));
            }
            wb.mark("surfaces.color_by.own");
            if (main && main->frame)
                for (const auto& [v, info] : wb.columns().of(main->frame)) {
                    const bool picked = ImGui::Selectable(v.c_str(), v == st.colorBy);
                    wb.mark("surfaces.color_by." + v);
                    if (picked && v != st.colorBy)
                        wb.emit(core::cmd::SurfaceSet(st.fault).colorBy(v).clearRange());
                }
            ImGui::EndCombo();
        }
        wb.mark("surfaces.color_by");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Figure 4: each voxel takes the colour of the spheres within their "
                              "radius + reach, averaged");
        flowSameLine(buttonWidth("Like the view"));
        // The main view's variable, map and range: the surface in the glyphs' colours.
        const core::ViewState* view = s.view("main");
        const bool viewColours = view && main && !view->colorVariable.empty() &&
                                 view->colorVariable != kFaultsVariable &&
                                 view->difference.mode == core::ColorDifference::Mode::None;
        ImGui::BeginDisabled(!viewColours);
        if (ImGui::Button("Like the view"))
            wb.emit(core::cmd::SurfaceSet(st.fault)
                        .colorBy(view->colorVariable)
                        .map(core::colorMapName(view->colorMap))
                        .range(main->colorRange[0], main->colorRange[1]));
        ImGui::EndDisabled();
        wb.mark("surfaces.like_view");
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("Colour the surface by the main view's variable, map and range");
        if (own) {
            if (m_editingColour != st.fault || !ImGui::IsAnyItemActive()) {
                for (int k = 0; k < 3; ++k)
                    m_colour[k] = static_cast<float>((*st.color)[k]);
                m_editingColour = st.fault;
            }
            ImGui::SetNextItemWidth(w);
            ImGui::ColorEdit3("surface colour", m_colour.data(), ImGuiColorEditFlags_NoInputs);
            if (ImGui::IsItemDeactivatedAfterEdit())
                wb.emit(core::cmd::SurfaceSet(st.fault).color(
                    std::array<double, 3>{m_colour[0], m_colour[1], m_colour[2]}));
            wb.mark("surfaces.colour");
        }
        if (!st.colorBy.empty()) {
            ImGui::SetNextItemWidth(w);
            const std::string currentMap = core::colorMapName(st.colorMap);
            if (ImGui::BeginCombo("map", currentMap.c_str())) {
                for (const std::string& m : core::colorMapNames())
                    if (ImGui::Selectable(m.c_str(), m == currentMap) && m != currentMap)
                        wb.emit(core::cmd::SurfaceSet(st.fault).map(m));
                ImGui::EndCombo();
            }
            if (st.colorRange)
                ImGui::TextDisabled("range %.4g .. %.4g", (*st.colorRange)[0], (*st.colorRange)[1]);
            else
                ImGui::TextDisabled("range: the frame's min to max");
            if (m_editingReach != st.fault || !ImGui::IsAnyItemActive()) {
                m_reach = st.colorReach.value_or(-1.0);
                m_editingReach = st.fault;
            }
            const bool reachTyped = numberField("reach", &m_reach, "%.3g", w, "auto", -1.0);
            if (m_reach < 0)
                m_reach = -1.0; // auto
            if (reachTyped && m_reach != st.colorReach.value_or(-1.0))
                wb.emit(core::cmd::SurfaceSet(st.fault).colorReach(
                    m_reach >= 0 ? std::optional(m_reach) : std::nullopt));
            wb.mark("surfaces.reach");
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("w: a voxel takes a sphere's colour within radius + w of its "
                                  "centre, else white. auto (or a negative value): twice the "
                                  "mean radius");
        }
    }
};

} // namespace

std::unique_ptr<Panel> makeSurfacesPanel() { return std::make_unique<SurfacesPanel>(); }

} // namespace faultline::ui
