// Index of this file:
// [SECTION] Helpers
// [SECTION] Commands for every view: presets, fit, projection
// [SECTION] Drawing a view and its header
// [SECTION] Tool buttons and popups: frame, colour, difference
// [SECTION] Mouse and keys: camera, selection, box handles

#include "ui/panels/viewport_cell.hpp"

#include "core/model/frame_difference.hpp"
#include "core/motion/strain_spec.hpp"
#include "core/selection/column_view.hpp"
#include "core/session/commands.hpp"
#include "core/view/box_handles.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/viewport/category_colors.hpp"
#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/viewport/orbit_camera.hpp"
#include "ui/widgets/number_field.hpp"
#include "ui/widgets/text_fit.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace faultline::ui {

namespace {

//-----------------------------------------------------------------------------
// [SECTION] Helpers
//-----------------------------------------------------------------------------

// Why a view coloured by a variable shows one colour: the shown frame lacks it (empty: it has
// it, or the view shows plain colour, categories or a difference).
std::string missingColourNote(const core::ViewState& view, const ViewDisplay& d) {
    if (!d.frame || view.colorVariable.empty() || view.colorVariable == kFaultsVariable ||
        !d.palette.empty() || d.colorColumn ||
        view.difference.mode != core::ColorDifference::Mode::None)
        return {};
    return core::missingVariableNote(*d.frame, view.colorVariable);
}

// Why a view coloured by a variable shows grey spheres: the frame has the column, without a
// value (strain from motion on a frame with no reference frame).
std::string noValueNote(const core::ViewState& view, const ViewDisplay& d,
                        const core::SessionState& state, std::size_t frameCount) {
    if (!d.colorHasNoValue)
        return {};
    std::string note = "no sphere has a value of '" + view.colorVariable + "' in this frame";
    // One of a strain's own variables, and the strain has no reference frame for this one.
    for (const core::StrainSpec& spec : state.strains)
        for (std::string_view v : core::kStrainVariables)
            if (view.colorVariable == spec.variable(v) &&
                !spec.referenceFor(d.shownFrame, frameCount))
                return note + (spec.relative
                                   ? " (strain from motion against " +
                                         std::to_string(std::llabs(spec.reference)) + " frame" +
                                         (std::llabs(spec.reference) == 1 ? "" : "s") +
                                         " away: this frame has none that far)"
                                   : " (its reference frame is not in the data)");
    return note;
}

std::string bindingText(const core::FrameBinding& b) {
    if (!b.relative)
        return "frame " + std::to_string(b.value);
    if (b.value == 0)
        return "current frame";
    return std::string("current ") + (b.value < 0 ? "- " : "+ ") +
           std::to_string(std::llabs(b.value));
}

glm::dvec3 faceCentre(const std::array<double, 3>& mn, const std::array<double, 3>& mx, int face) {
    glm::dvec3 c(0.5 * (mn[0] + mx[0]), 0.5 * (mn[1] + mx[1]), 0.5 * (mn[2] + mx[2]));
    const int axis = face / 2;
    c[axis] = face % 2 ? mx[axis] : mn[axis];
    return c;
}

double sceneRadius(const ViewDisplay& d) { return d.frame ? d.sceneRadius : 1.0; }

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] Commands for every view: presets, fit, projection
//-----------------------------------------------------------------------------

void ViewportCells::emitForViews(
    PanelContext& wb, const std::function<void(const std::string&, core::cmd::CameraSet&)>& fill) {
    std::vector<core::Json> batch;
    bool mainDone = false;
    for (const auto& v : wb.state().views) {
        if (v.linkedCamera && mainDone)
            continue; // follows the main view
        core::cmd::CameraSet cmd(v.name);
        fill(v.name, cmd);
        batch.push_back(std::move(cmd));
        if (v.linkedCamera)
            mainDone = true;
    }
    if (!batch.empty())
        wb.emit(core::cmd::batch(std::move(batch)));
}

void ViewportCells::presetAll(PanelContext& wb, const char* preset) {
    // Looking from another side changes what fits: each view is fitted again to its visible
    // spheres (as Fit visible does), so the model is never cropped by the old zoom.
    core::CameraState p;
    applyPreset(p, preset);
    emitForViews(wb, [&](const std::string& view, core::cmd::CameraSet& cmd) {
        cmd.azimuth(p.azimuth).elevation(p.elevation);
        fitVisibleInto(wb, view, cmd, &p);
    });
}

void ViewportCells::fitAll(PanelContext& wb) {
    emitForViews(wb, [](const std::string&, core::cmd::CameraSet& cmd) { cmd.distance(0.0); });
}

void ViewportCells::fitVisibleInto(PanelContext& wb, const std::string& name,
                                   core::cmd::CameraSet& cmd,
                                   const core::CameraState* orientation) {
    const ViewDisplay* d = wb.view(name);
    const core::ViewState* v = wb.state().view(name);
    if (!d || !v || !d->frame || !d->visibility || d->visibility->visibleCount == 0) {
        cmd.distance(0.0); // nothing visible: the whole model
        return;
    }
    core::CameraState camera = d->camera;
    if (orientation)
        camera.azimuth = orientation->azimuth, camera.elevation = orientation->elevation;
    const auto bounds = visibleBounds(*d->frame, d->visibility->mask);
    const core::CameraState c = wb.fitCamera(*v, camera, bounds.lo, bounds.hi);
    cmd.target(c.target).distance(c.distance);
}

void ViewportCells::fitVisible(PanelContext& wb) {
    emitForViews(wb, [&wb, this](const std::string& view, core::cmd::CameraSet& cmd) {
        fitVisibleInto(wb, view, cmd, nullptr);
    });
}

void ViewportCells::setOrthographic(PanelContext& wb, bool ortho) {
    emitForViews(wb, [&](const std::string& view, core::cmd::CameraSet& cmd) {
        cmd.orthographic(ortho);
        // Keep the display's fitted distance instead of "unset".
        if (const ViewDisplay* d = wb.view(view))
            cmd.distance(d->camera.distance).target(d->camera.target);
    });
}

//-----------------------------------------------------------------------------
// [SECTION] Drawing a view and its header
//-----------------------------------------------------------------------------

void ViewportCells::draw(PanelContext& wb, const core::ViewState& view, ImVec2 pos, ImVec2 size) {
    const ViewDisplay* dp = wb.view(view.name);
    static const ViewDisplay kEmpty;
    const ViewDisplay& d = dp ? *dp : kEmpty;
    ImGui::PushID(view.name.c_str());
    const float headerH = headerHeight(wb, size.x);
    drawHeader(wb, view, d, pos, size.x);
    const ImVec2 imgPos(pos.x, pos.y + headerH);
    const ImVec2 imgSize(size.x, std::max(1.0f, size.y - headerH));
    ImGui::SetCursorScreenPos(imgPos);
    ImGui::InvisibleButton("##image", imgSize,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                               ImGuiButtonFlags_MouseButtonMiddle);
    wb.mark("view.image." + view.name);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 imgMax(imgPos.x + imgSize.x, imgPos.y + imgSize.y);
    const unsigned int tex = wb.renderer() ? wb.renderer()->texture(view.name) : 0;
    std::array<std::string, 2> placeholder; // the text shown where there is no image (yet)
    if (tex) {
        dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(tex)), imgPos,
                     imgMax, ImVec2(0, 1), ImVec2(1, 0));
    } else {
        // No renderer in this build or run: a clear placeholder, with outlines drawn below.
        dl->AddRectFilledMultiColor(imgPos, imgMax, IM_COL32(250, 251, 253, 255),
                                    IM_COL32(250, 251, 253, 255), IM_COL32(226, 230, 238, 255),
                                    IM_COL32(226, 230, 238, 255));
        const char* line1 =
            wb.renderer() ? "rendering..." : "3-D spheres are not drawn in this build";
        // Drawn last (below), over the box outlines and member marks, so they never hide it.
        std::string line2 =
            d.frame ? std::to_string(d.frame->size()) + " spheres, " +
                          std::to_string(d.visibility ? d.visibility->visibleCount : 0) + " visible"
                    : std::string("no data: File > Open data, or drop a file here");
        placeholder = {line1, line2};
    }
    if (!d.frame) {
        // Data on its way (the first run builds the demo): say what, and how far, in the view
        // too (issue 41: only the status bar showed it while the view said "No data").
        for (const auto& job : wb.jobs().running()) {
            const std::string title = job->title();
            if (title.rfind("Making the demo", 0) != 0 && title.rfind("Opening", 0) != 0)
                continue;
            const float p = job->progress();
            placeholder = {title + (p >= 0 ? "  " + std::to_string(int(p * 100)) + "%" : "..."),
                           title.rfind("Making the demo", 0) == 0
                               ? "The first run builds the 3-D demo once: about 90 s on 2 cores"
                               : ""};
            break;
        }
        if (tex && placeholder[0].empty())
            placeholder = {"No data: File > Open data, or drop a file here", ""};
    }
    interact(wb, view, d, imgPos, imgSize);
    const core::CameraState cam =
        m_drag.mode != DragMode::None && m_drag.mode != DragMode::BoxFace &&
                m_drag.view == view.name
            ? m_drag.current
            : (m_wheel && m_wheel->view == view.name ? m_wheel->camera : d.camera);
    dl->PushClipRect(imgPos, imgMax, true);
    drawOverlays(wb, view, d, cam, imgPos, imgSize);
    m_selection.drawMembers(wb, d, cam, imgPos, imgSize);
    if (m_selection.view() == view.name)
        m_selection.drawOutline(dl, wb.scale());
    const float cx = imgPos.x + imgSize.x * 0.5f, cy = imgPos.y + imgSize.y * 0.5f;
    // Below the frame label (two lines at most) and above the axes, or not at all in a view too
    // short for both.
    const float lineH = ImGui::GetTextLineHeightWithSpacing();
    if (imgSize.y < 6 * lineH + 8 * wb.scale())
        placeholder = {};
    for (int k = 0; k < 2; ++k)
        if (!placeholder[k].empty()) {
            placeholder[k] = elided(placeholder[k], imgSize.x - 8 * wb.scale()); // narrow views
            const ImVec2 t = ImGui::CalcTextSize(placeholder[k].c_str());
            dl->AddText(ImVec2(cx - t.x * 0.5f, k == 0 ? cy - t.y : cy + 4),
                        IM_COL32(110, 116, 128, 255), placeholder[k].c_str());
        }
    dl->PopClipRect();
    ImGui::PopID();
}

// A view narrower than this puts its colour and linked box on a second header row (issue 41:
// three views side by side in a 640-pixel window cut the frame and colour buttons).
float ViewportCells::headerHeight(PanelContext& wb, float width) {
    const float row = ImGui::GetFrameHeight() + 6 * wb.scale();
    return width < kTwoRowHeader * wb.scale() ? row + ImGui::GetFrameHeightWithSpacing() : row;
}

void ViewportCells::drawHeader(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d,
                               ImVec2 pos, float width) {
    const float scale = wb.scale();
    const float h = headerHeight(wb, width);
    const bool twoRows = width < kTwoRowHeader * scale;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(pos, ImVec2(pos.x + width, pos.y + h),
                      ImGui::GetColorU32(ImGuiCol_MenuBarBg));
    ImGui::SetCursorScreenPos(ImVec2(pos.x + 6 * scale, pos.y + 3 * scale));
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(view.name.c_str());
    ImGui::SameLine();
    // Frame binding, shortened to what the row leaves (the tooltip says it all).
    const std::string fullBinding = bindingText(view.frame);
    float bindingRoom = pos.x + width - 6 * scale - ImGui::GetCursorScreenPos().x -
                        2 * ImGui::GetStyle().FramePadding.x;
    // The close button ends the first row, or the second in a two-row header (a view a third
    // of 300 pixels wide left the frame binding no room beside it: its "..." lay under the x).
    if (view.name != "main" && !twoRows)
        bindingRoom -= ImGui::GetFrameHeight() + ImGui::GetStyle().ItemSpacing.x;
    const std::string binding =
        twoRows ? elided(fullBinding, std::max(bindingRoom, ImGui::CalcTextSize("...").x))
                : fullBinding;
    if (ImGui::Button((binding + "##binding").c_str())) {
        m_frameRelative = view.frame.relative;
        m_frameEdit = static_cast<int>(view.frame.value);
        ImGui::OpenPopup("##framepopup");
    }
    wb.mark("view.binding." + view.name);
    if (ImGui::IsItemHovered() && wb.dataset())
        ImGui::SetTooltip(
            "Shows frame %zu (timestep %lld). Click to bind this view to another frame.",
            d.wantedFrame, static_cast<long long>(wb.dataset()->location(d.wantedFrame).timestep));
    drawFramePopup(wb, view);
    if (twoRows)
        ImGui::SetCursorScreenPos(
            ImVec2(pos.x + 6 * scale, pos.y + 3 * scale + ImGui::GetFrameHeightWithSpacing()));
    else
        ImGui::SameLine();
    // Colour: the button takes what is left of the header beside the linked box and the close
    // button, its label shortened to fit (the whole of it in the tooltip). Categories (faults,
    // candidates) have no colour map to name.
    const std::string title = d.colorTitle.empty() ? view.colorVariable : d.colorTitle;
    // A variable this frame lacks (strain removed, a column another file of the series does
    // not have): the spheres are in one colour, and the button says why rather than naming a
    // colour map that shows nothing.
    const std::string missing = missingColourNote(view, d);
    const std::string noValue =
        noValueNote(view, d, wb.state(), wb.dataset() ? wb.dataset()->frameCount() : 0);
    const std::string colour = title.empty()      ? std::string("plain colour")
                               : !missing.empty() ? title + " (not in this frame)"
                               : !noValue.empty() ? title + " (no values in this frame)"
                               : !d.palette.empty()
                                   ? title
                                   : title + " (" + core::colorMapName(view.colorMap) + ")";
    const ImGuiStyle& style = ImGui::GetStyle();
    float reserve = 0.0f;
    // In a narrow view the linked box goes without its label (the tooltip says it).
    const bool narrow = width < 340 * scale;
    const char* linkedLabel = narrow ? "##linked" : "linked";
    if (wb.state().views.size() > 1)
        reserve +=
            (narrow ? ImGui::GetFrameHeight() : checkboxWidth("linked")) + style.ItemSpacing.x;
    if (view.name != "main")
        reserve += ImGui::GetFrameHeight() + style.ItemSpacing.x;
    const float room = pos.x + width - 6 * scale - ImGui::GetCursorScreenPos().x - reserve -
                       2 * style.FramePadding.x;
    const std::string shown = elided(colour, std::max(room, ImGui::CalcTextSize("...").x));
    if (ImGui::Button((shown + "##colour").c_str())) {
        m_rangeEdit[0] = m_rangeShown[0] = d.colorRange[0];
        m_rangeEdit[1] = m_rangeShown[1] = d.colorRange[1];
        m_sinceRelative = view.difference.reference.relative;
        m_sinceEdit = static_cast<int>(view.difference.reference.value);
        ImGui::OpenPopup("##colourpopup");
    }
    if (!missing.empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: the spheres are in one colour.\nClick to colour by another "
                          "variable.",
                          missing.c_str());
    else if (!noValue.empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: the spheres are grey.", noValue.c_str());
    else if (shown != colour && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", colour.c_str());
    wb.mark("view.colour." + view.name);
    if (!missing.empty())
        wb.mark("view.colour.missing." + view.name);
    if (!noValue.empty())
        wb.mark("view.colour.novalue." + view.name);
    drawColourPopup(wb, view, d);
    ImGui::SameLine();
    if (wb.state().views.size() > 1) {
        bool linked = view.linkedCamera;
        if (ImGui::Checkbox(linkedLabel, &linked))
            wb.emit(core::cmd::ViewSet(view.name).linkedCamera(linked));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Linked cameras move together; unlink to look at this view on its own.");
    }
    if (view.name != "main") {
        const float bw = ImGui::GetFrameHeight();
        ImGui::SameLine();
        const float rowY =
            pos.y + 3 * scale + (twoRows ? ImGui::GetFrameHeightWithSpacing() : 0.0f);
        ImGui::SetCursorScreenPos(ImVec2(pos.x + width - bw - 6 * scale, rowY));
        if (ImGui::Button("x", ImVec2(bw, 0)))
            wb.emit(core::cmd::viewRemove(view.name));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Close this view");
    }
}

//-----------------------------------------------------------------------------
// [SECTION] Tool buttons and popups: frame, colour, difference
//-----------------------------------------------------------------------------

// What the selection tools do, for their tooltips.
constexpr const char* kSelectHelp =
    "\nThe spheres you can see inside it (every visible one front to back\n"
    "with \"through the depth\") go into the selected fault, or make a\n"
    "new fault when none is selected.\n"
    "Ctrl+drag: take them out of it. Shift+drag: a new fault.\n"
    "A click toggles one sphere; right drag pans.";

void ViewportCells::drawToolButtons(PanelContext& wb) {
    static const struct {
        ViewportTool tool;
        const char* label;
        const char* mark;
        const char* tip;
    } kTools[] = {
        {ViewportTool::Orbit, "Orbit", "orbit",
         "Left drag orbits, right drag pans (Esc).\n"
         "Ctrl+click a sphere: into the selected fault, or out of it."},
        {ViewportTool::Rectangle, "Rectangle", "rectangle", "Drag a rectangle around spheres (R)."},
        {ViewportTool::Lasso, "Lasso", "lasso", "Draw a loop around spheres (L)."},
    };
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(1, ImGui::GetStyle().ItemSpacing.y));
    for (const auto& t : kTools) {
        const bool on = wb.selection().tool == t.tool;
        if (on)
            ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetColorU32(ImGuiCol_ButtonActive));
        if (ImGui::Button(t.label))
            wb.selection().tool = t.tool;
        if (on)
            ImGui::PopStyleColor();
        wb.mark(std::string("viewports.tool.") + t.mark);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s%s", t.tip, t.tool == ViewportTool::Orbit ? "" : kSelectHelp);
        if (t.tool != ViewportTool::Lasso)
            ImGui::SameLine();
    }
    // While a shape tool is on: the spheres in view (default) or all through the depth.
    if (wb.selection().tool != ViewportTool::Orbit) {
        flowSameLine(checkboxWidth("through the depth")); // on the next row when it would not fit
        ImGui::Checkbox("through the depth", &wb.selection().throughDepth);
        wb.mark("viewports.through_depth");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Off: the rectangle or lasso takes the spheres you can see.\n"
                              "On: every visible sphere whose centre is inside, front to back.");
    }
    ImGui::PopStyleVar();
}

void ViewportCells::drawFramePopup(PanelContext& wb, const core::ViewState& view) {
    if (!ImGui::BeginPopup("##framepopup"))
        return;
    ImGui::TextUnformatted("This view shows");
    if (ImGui::RadioButton("the current frame plus", m_frameRelative))
        m_frameRelative = true;
    if (ImGui::RadioButton("a fixed frame", !m_frameRelative))
        m_frameRelative = false;
    ImGui::SetNextItemWidth(120 * wb.scale());
    ImGui::InputInt(m_frameRelative ? "frames" : "frame", &m_frameEdit);
    if (!m_frameRelative)
        m_frameEdit = std::max(0, m_frameEdit);
    if (ImGui::Button("Apply") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter))) {
        wb.emit(m_frameRelative ? core::cmd::ViewSet(view.name).offset(m_frameEdit)
                                : core::cmd::ViewSet(view.name).frame(m_frameEdit));
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

void ViewportCells::drawColourPopup(PanelContext& wb, const core::ViewState& view,
                                    const ViewDisplay& d) {
    if (!ImGui::BeginPopup("##colourpopup"))
        return;
    ImGui::TextDisabled("Colour by");
    if (ImGui::Selectable("plain colour", view.colorVariable.empty()))
        wb.emit(core::cmd::ColorSet(view.name).variable(""));
    if (ImGui::Selectable("faults (each in its colour)", view.colorVariable == kFaultsVariable))
        wb.emit(core::cmd::ColorSet(view.name)
                    .variable(kFaultsVariable)
                    .difference(core::ColorDifference::Mode::None));
    if (d.frame)
        for (const auto& [v, info] : wb.columns().of(d.frame))
            if (ImGui::Selectable(v.c_str(), v == view.colorVariable))
                wb.emit(core::cmd::ColorSet(view.name).variable(v).rangeMode(
                    view.rangeMode == core::RangeMode::Fixed ? core::RangeMode::CurrentFrame
                                                             : view.rangeMode));
    ImGui::Separator();
    ImGui::TextDisabled("Colour map");
    for (const std::string& m : core::colorMapNames())
        if (ImGui::Selectable(m.c_str(), core::colorMapName(view.colorMap) == m))
            wb.emit(core::cmd::ColorSet(view.name).map(m));
    ImGui::Separator();
    ImGui::TextDisabled("Range");
    const struct {
        core::RangeMode mode;
        const char* label;
    } modes[] = {{core::RangeMode::CurrentFrame, "this frame's min to max (spheres shown)"},
                 {core::RangeMode::Percentile, "this frame's 1st to 99th percentile (shown)"},
                 {core::RangeMode::AllFrames, "all frames (steady in playback)"},
                 {core::RangeMode::Fixed, "fixed"}};
    // The range the colours take (core::effectiveRangeMode): a change or displacement spans
    // all frames unless fixed, so there "this frame's" is off and says why (issue 41).
    const bool difference = view.difference.mode != core::ColorDifference::Mode::None;
    for (const auto& m : modes) {
        const std::string_view mode = core::rangeModeName(m.mode);
        const bool on = core::effectiveRangeMode(view) == m.mode;
        const bool off = difference && (m.mode == core::RangeMode::CurrentFrame ||
                                        m.mode == core::RangeMode::Percentile);
        ImGui::BeginDisabled(off);
        if (ImGui::RadioButton(m.label, on) && !on) {
            core::cmd::ColorSet cmd(view.name);
            cmd.rangeMode(m.mode);
            if (m.mode == core::RangeMode::Fixed)
                cmd.range(d.colorRange[0], d.colorRange[1]);
            wb.emit(cmd);
        }
        wb.mark("view.range." + std::string(mode) + "." + view.name);
        ImGui::EndDisabled();
        if (off && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("A change or a displacement is coloured over all frames (or a "
                              "fixed range),\nso that a colour means the same at every frame.");
    }
    // The fields follow the range shown while the popup is open (a change colouring chosen in
    // it brings another range), unless the user is typing in them.
    if ((d.colorRange[0] != m_rangeShown[0] || d.colorRange[1] != m_rangeShown[1]) &&
        !ImGui::IsAnyItemActive()) {
        m_rangeEdit[0] = m_rangeShown[0] = d.colorRange[0];
        m_rangeEdit[1] = m_rangeShown[1] = d.colorRange[1];
    }
    const bool loDone = numberField("##lo", &m_rangeEdit[0], "%.5g", 110 * wb.scale());
    wb.mark("view.range.low." + view.name);
    ImGui::SameLine();
    const bool hiDone = numberField("##hi", &m_rangeEdit[1], "%.5g", 110 * wb.scale());
    wb.mark("view.range.high." + view.name);
    if ((loDone || hiDone) && m_rangeEdit[0] < m_rangeEdit[1])
        wb.emit(core::cmd::ColorSet(view.name).range(m_rangeEdit[0], m_rangeEdit[1]));
    // A fixed range over the middle 98 % of the spheres shown, for variables whose few extreme
    // values (grains thrown out of a model: strain from motion in the hundreds) leave every
    // other sphere one colour.
    ImGui::BeginDisabled(difference || !d.frame || !d.visibility);
    if (ImGui::Button("1st to 99th percentile") && d.frame && d.visibility)
        if (const auto q =
                core::maskedQuantiles(*d.frame, view.colorVariable, d.visibility->mask, 0.01, 0.99);
            q && q->first < q->second)
            wb.emit(core::cmd::ColorSet(view.name)
                        .rangeMode(core::RangeMode::Fixed)
                        .range(q->first, q->second));
    wb.mark("view.range.fix_percentile." + view.name); // not the "percentile" mode's
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip(difference ? "Not for a change or a displacement colouring"
                                     : "A fixed range from the 1st to the 99th percentile of the "
                                       "spheres shown:\na few extreme values no longer leave "
                                       "the others one colour.");
    drawDifference(wb, view);
    ImGui::EndPopup();
}

// Difference colouring: the variable's change, or the distance moved, since a reference frame.
void ViewportCells::drawDifference(PanelContext& wb, const core::ViewState& view) {
    using Mode = core::ColorDifference::Mode;
    ImGui::Separator();
    ImGui::TextDisabled("Show");
    const struct {
        Mode mode;
        const char* label;
    } modes[] = {{Mode::None, "the value itself"},
                 {Mode::Change, "its change since a frame"},
                 {Mode::Displacement, "displacement since a frame"}};
    auto since = [&](core::cmd::ColorSet cmd) {
        if (m_sinceRelative)
            cmd.sinceOffset(m_sinceEdit);
        else
            cmd.sinceFrame(m_sinceEdit);
        wb.emit(cmd);
    };
    for (const auto& m : modes) {
        const bool needsVariable = m.mode == Mode::Change && view.colorVariable.empty();
        if (needsVariable)
            ImGui::BeginDisabled();
        if (ImGui::RadioButton(m.label, view.difference.mode == m.mode) &&
            view.difference.mode != m.mode)
            since(core::cmd::ColorSet(view.name).difference(m.mode));
        if (needsVariable)
            ImGui::EndDisabled();
    }
    if (view.difference.mode == Mode::None)
        return;
    if (ImGui::RadioButton("frame", !m_sinceRelative))
        m_sinceRelative = false, m_sinceEdit = std::max(0, m_sinceEdit);
    ImGui::SameLine();
    if (ImGui::RadioButton("offset from the frame shown (e.g. -10)", m_sinceRelative))
        m_sinceRelative = true, m_sinceEdit = -std::abs(m_sinceEdit);
    const bool edited = numberField("##since", &m_sinceEdit, 110 * wb.scale());
    // Enter applies even when the number typed is the one shown (issue 41).
    const bool enter = ImGui::IsItemDeactivated() &&
                       ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter), false);
    wb.mark("view.since." + view.name);
    if (!m_sinceRelative)
        m_sinceEdit = std::max(0, m_sinceEdit);
    ImGui::SameLine();
    const bool apply = ImGui::Button("Apply##since");
    wb.mark("view.since_apply." + view.name);
    if (apply || edited || enter) {
        since(core::cmd::ColorSet(view.name));
        ImGui::CloseCurrentPopup(); // applied: the popup has done its job
    }
}

//-----------------------------------------------------------------------------
// [SECTION] Mouse and keys: camera, selection, box handles
//-----------------------------------------------------------------------------

void ViewportCells::interact(PanelContext& wb, const core::ViewState& view, const ViewDisplay& d,
                             ImVec2 pos, ImVec2 size) {
    const ImGuiIO& io = ImGui::GetIO();
    const bool hovered = ImGui::IsItemHovered();
    const bool active = ImGui::IsItemActive();
    const double aspect = size.x / std::max(1.0f, size.y);

    // Which face handle of the selected box the mouse is over: a ray from the eye through the
    // cursor against the handle spheres the renderer draws (core/view/box_handles).
    const core::CuttingBox* box =
        wb.selection().editBoxInView ? wb.state().box(wb.selection().box) : nullptr;
    auto rayAt = [&](ImVec2 mouse, const core::CameraState& cam) {
        const glm::dvec2 ndc((mouse.x - pos.x) / size.x * 2.0 - 1.0,
                             1.0 - (mouse.y - pos.y) / size.y * 2.0);
        return core::cameraRay(toRenderCamera(cam), ndc, aspect);
    };
    if (hovered && m_drag.mode == DragMode::None) {
        m_hoverFace = -1;
        m_hoverView = view.name;
        if (box && d.frame) {
            const glm::dvec3 lo(box->min[0], box->min[1], box->min[2]),
                hi(box->max[0], box->max[1], box->max[2]);
            const core::Ray ray = rayAt(io.MousePos, d.camera);
            const double r = core::screenHandleRadius(lo, hi, d.camera.distance, d.camera.fovY);
            double best = 1e300;
            for (const core::BoxHandle& h : core::boxFaceHandles(lo, hi))
                if (auto t = core::intersectSphere(ray, h.centre, r); t && *t < best)
                    best = *t, m_hoverFace = static_cast<int>(h.face);
        }
    }
    if (ImGui::IsItemActivated()) {
        m_drag = Drag{};
        m_drag.view = view.name;
        m_drag.start = d.camera;
        m_drag.current = d.camera;
        m_drag.startMouse = io.MousePos;
        const bool otherButton = ImGui::IsMouseDown(ImGuiMouseButton_Right) ||
                                 ImGui::IsMouseDown(ImGuiMouseButton_Middle);
        const bool panButton =
            otherButton || (io.KeyShift && wb.selection().tool == ViewportTool::Orbit);
        if (!otherButton && m_selection.press(wb, view.name, io.MousePos)) {
            m_drag.mode = DragMode::Select;
        } else if (!panButton && m_hoverFace >= 0 && m_hoverView == view.name && box) {
            m_drag.mode = DragMode::BoxFace;
            m_drag.face = m_hoverFace;
            m_drag.boxMin = box->min;
            m_drag.boxMax = box->max;
        } else {
            m_drag.mode = panButton ? DragMode::Pan : DragMode::Orbit;
        }
    }
    if (active && m_drag.view == view.name && m_drag.mode == DragMode::Select) {
        m_selection.drag(io.MousePos, wb.scale());
        if (m_selection.becameOrbit()) {
            m_selection.cancel();
            m_drag.mode = DragMode::Orbit;
        }
    } else if (active && m_drag.view == view.name && m_drag.mode != DragMode::None) {
        const double dx = io.MousePos.x - m_drag.startMouse.x,
                     dy = io.MousePos.y - m_drag.startMouse.y;
        if (m_drag.mode == DragMode::BoxFace && box) {
            // The face follows the cursor along its axis (exact under perspective).
            const glm::dvec3 lo(m_drag.boxMin[0], m_drag.boxMin[1], m_drag.boxMin[2]);
            const glm::dvec3 hi(m_drag.boxMax[0], m_drag.boxMax[1], m_drag.boxMax[2]);
            const core::BoxBounds moved =
                core::dragBoxFace(lo, hi, static_cast<core::BoxFace>(m_drag.face),
                                  rayAt(m_drag.startMouse, d.camera), rayAt(io.MousePos, d.camera));
            const std::array<double, 3> mn{moved.lo.x, moved.lo.y, moved.lo.z},
                mx{moved.hi.x, moved.hi.y, moved.hi.z};
            const core::Json cmd = core::cmd::BoxSet(box->name).min(mn).max(mx);
            wb.preview("viewport.box", cmd);
            m_pendingBox = cmd;
        } else if (dx != 0 || dy != 0) {
            core::CameraState c = m_drag.start;
            if (m_drag.mode == DragMode::Orbit)
                orbit(c, dx, dy);
            else
                pan(c, dx, dy, size.y);
            m_drag.current = c;
            const core::Json cmd = core::cmd::CameraSet(view.name).all(c);
            wb.preview("viewport.camera", cmd);
        }
        if (m_drag.mode != DragMode::BoxFace)
            ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeAll);
    }
    if (ImGui::IsItemDeactivated() && m_drag.view == view.name) {
        if (m_drag.mode == DragMode::Select) {
            m_selection.release(wb, d, io.MousePos, pos, size);
        } else if (m_drag.mode == DragMode::BoxFace) {
            if (!m_pendingBox.is_null())
                wb.emit(m_pendingBox);
        } else if (m_drag.mode != DragMode::None && !(m_drag.current == m_drag.start)) {
            const core::Json cmd = core::cmd::CameraSet(view.name).all(m_drag.current);
            wb.emit(cmd);
        }
        m_pendingBox = nullptr;
        m_drag = Drag{};
    }
    if (hovered && m_hoverFace >= 0 && m_drag.mode == DragMode::None)
        ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
    if (m_drag.mode == DragMode::BoxFace)
        wb.selection().activeBoxFace = m_drag.face;
    else if (hovered)
        wb.selection().activeBoxFace = m_hoverFace;

    // Wheel zoom: previewed; one camera.set once the wheel has rested.
    if (hovered && io.MouseWheel != 0 && d.frame) {
        if (!m_wheel || m_wheel->view != view.name)
            m_wheel = Wheel{view.name, d.camera, 0};
        zoom(m_wheel->camera, std::pow(1.15, io.MouseWheel));
        m_wheel->lastTime = wb.now();
    }
    if (m_wheel && m_wheel->view == view.name) {
        const core::Json cmd = core::cmd::CameraSet(view.name).all(m_wheel->camera);
        if (wb.now() - m_wheel->lastTime > 0.4) {
            wb.emit(cmd);
            m_wheel.reset();
        } else {
            wb.preview("viewport.wheel", cmd);
        }
    }
}

void ViewportCells::drawOverlays(PanelContext& wb, const core::ViewState& view,
                                 const ViewDisplay& d, const core::CameraState& cam, ImVec2 pos,
                                 ImVec2 size) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float scale = wb.scale();
    const double aspect = size.x / std::max(1.0f, size.y);
    const glm::dmat4 vp = projectionMatrix(cam, aspect, sceneRadius(d)) * viewMatrix(cam);
    auto px = [&](const glm::dvec3& p) -> std::optional<ImVec2> {
        auto q = projectToPixels(vp, p, glm::dvec2(size.x, size.y));
        if (!q)
            return std::nullopt;
        return ImVec2(pos.x + static_cast<float>(q->x), pos.y + static_cast<float>(q->y));
    };
    auto boxEdges = [&](const std::array<double, 3>& mn, const std::array<double, 3>& mx,
                        ImU32 color, float thickness) {
        glm::dvec3 corner[8];
        for (int k = 0; k < 8; ++k)
            corner[k] =
                glm::dvec3(k & 1 ? mx[0] : mn[0], k & 2 ? mx[1] : mn[1], k & 4 ? mx[2] : mn[2]);
        for (int a = 0; a < 8; ++a)
            for (int bit = 1; bit < 8; bit <<= 1)
                if (!(a & bit)) {
                    auto p = px(corner[a]), q = px(corner[a | bit]);
                    if (p && q)
                        dl->AddLine(*p, *q, color, thickness);
                }
    };
    const bool placeholder = !wb.renderer();
    if (d.frame && placeholder) {
        const ModelBounds& b = d.bounds;
        boxEdges(b.lo, b.hi, IM_COL32(150, 156, 168, 255), 1.0f * scale);
    }
    // Boxes and handles, unless the renderer draws them into the image.
    const bool drawBoxes = !wb.renderer() || !wb.renderer()->drawsBoxes();
    for (const auto& b : wb.displayBoxes()) {
        if (!drawBoxes)
            break;
        if (!b.enabled && b.name != wb.selection().box)
            continue;
        const bool sel = b.name == wb.selection().box;
        const ImU32 col = b.mode == core::BoxMode::Keep ? IM_COL32(40, 140, 70, sel ? 255 : 170)
                                                        : IM_COL32(200, 70, 40, sel ? 255 : 170);
        boxEdges(b.min, b.max, col, (sel ? 2.0f : 1.2f) * scale);
        if (sel && wb.selection().editBoxInView)
            for (int f = 0; f < 6; ++f)
                if (auto p = px(faceCentre(b.min, b.max, f))) {
                    const bool lit = (m_hoverFace == f && m_hoverView == view.name) ||
                                     (m_drag.mode == DragMode::BoxFace && m_drag.face == f);
                    dl->AddCircleFilled(*p, (lit ? 7.0f : 5.5f) * scale,
                                        lit ? IM_COL32(255, 170, 40, 255)
                                            : IM_COL32(255, 255, 255, 255));
                    dl->AddCircle(*p, (lit ? 7.0f : 5.5f) * scale, col, 16, 1.5f * scale);
                }
    }
    // Axes: east, north, up, in the lower left corner; smaller in a small view, where the full
    // size covered the model (issue 41: a 640x420 window).
    const CameraBasis basis = cameraBasis(cam);
    const float triad = scale * std::clamp(std::min(size.x, size.y) / (360.0f * scale), 0.6f, 1.0f);
    const ImVec2 o(pos.x + 38 * triad, pos.y + size.y - 38 * triad);
    const struct {
        glm::dvec3 dir;
        const char* label;
        ImU32 color;
    } axes[] = {{{1, 0, 0}, "E", IM_COL32(200, 60, 50, 255)},
                {{0, 1, 0}, "N", IM_COL32(50, 150, 60, 255)},
                {{0, 0, 1}, "Up", IM_COL32(50, 90, 200, 255)}};
    float pointingAt = 0;       // labels of axes seen end-on, stacked beside the origin
    std::vector<ImVec4> placed; // the labels drawn so far (x0, y0, x1, y1)
    // A view under 150 pixels tall has no room for the axes beside the model and its labels.
    const bool roomForAxes = size.y >= 150 * scale;
    for (const auto& a : axes) {
        if (!roomForAxes)
            break;
        const float dx = static_cast<float>(glm::dot(a.dir, basis.right)) * 26 * triad;
        const float dy = static_cast<float>(glm::dot(a.dir, basis.up)) * 26 * triad;
        const ImVec2 e(o.x + dx, o.y - dy);
        dl->AddLine(o, e, a.color, 2.0f * scale);
        if (std::hypot(dx, dy) < 9 * triad) {
            // Seen end-on (North in a Front view): a dot, the label to the left of the origin
            // (issue 41: "Up" and "N" were drawn over each other).
            dl->AddCircleFilled(o, 2.5f * scale, a.color);
            dl->AddText(ImVec2(o.x - 16 * scale, o.y - 7 * scale + pointingAt), a.color, a.label);
            pointingAt += 13 * scale;
            continue;
        }
        // Clear of the labels already placed ("Up" and "N" touched in oblique views).
        ImVec2 at(e.x + 2 * scale, e.y - 7 * scale);
        const ImVec2 size = ImGui::CalcTextSize(a.label);
        for (const ImVec4& r : placed)
            if (at.x < r.z && at.x + size.x > r.x && at.y < r.w && at.y + size.y > r.y)
                at.x = r.z + 2 * scale;
        placed.push_back(ImVec4(at.x, at.y, at.x + size.x, at.y + size.y));
        dl->AddText(at, a.color, a.label);
    }
    // Frame label, top left; loading state.
    if (auto ds = wb.dataset(); ds && d.frame) {
        char text[128];
        const long long timestep = static_cast<long long>(ds->location(d.shownFrame).timestep);
        std::snprintf(text, sizeof text, "frame %zu   timestep %lld", d.shownFrame, timestep);
        float line = 0;
        const ImU32 ink = IM_COL32(60, 64, 72, 255);
        if (ImGui::CalcTextSize(text).x + 16 * scale <= size.x) {
            dl->AddText(ImVec2(pos.x + 8 * scale, pos.y + 6 * scale), ink, text);
            line = 1;
        } else { // a narrow view: one per line (issue 41: "frame 29 timeste" was cut)
            std::snprintf(text, sizeof text, "frame %zu", d.shownFrame);
            dl->AddText(ImVec2(pos.x + 8 * scale, pos.y + 6 * scale), ink, text);
            std::snprintf(text, sizeof text, "timestep %lld", timestep);
            const std::string step = elided(text, size.x - 16 * scale);
            dl->AddText(ImVec2(pos.x + 8 * scale, pos.y + 6 * scale + ImGui::GetTextLineHeight()),
                        ink, step.c_str());
            line = 2;
        }
        if (d.loading()) {
            std::snprintf(text, sizeof text, "loading frame %zu...", d.wantedFrame);
            dl->AddText(ImVec2(pos.x + 8 * scale,
                               pos.y + 6 * scale + line * ImGui::GetTextLineHeightWithSpacing()),
                        IM_COL32(190, 110, 20, 255), text);
        }
    }
}

} // namespace faultline::ui
