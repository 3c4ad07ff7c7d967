#include "ui/panels/strain_section.hpp"

#include "core/data/frame_cache.hpp"
#include "core/data/frame_prefetcher.hpp"
#include "core/motion/strain_from_motion.hpp"
#include "core/session/commands.hpp"
#include "core/session/items/strain_codec.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/widgets/number_field.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace faultline::ui {

namespace {

std::string describe(const core::StrainSpec& s) {
    std::string text = s.relative ? "against " + std::to_string(-s.reference) + " frame" +
                                        (s.reference == -1 ? "" : "s") + " before"
                                  : "since frame " + std::to_string(s.reference);
    if (s.relative && s.reference > 0)
        text = "against " + std::to_string(s.reference) + " frames after";
    text += s.cutoff > 0 ? ", cutoff " + numberText(s.cutoff) : ", cutoff auto";
    return text;
}

// Why the background pass leaves frames to be derived when shown ("" when it does not), with
// the frame cache's last problem when it refused a frame.
std::string heldText(const core::FramePrefetcher::BackgroundProgress& pass,
                     const core::Dataset& ds) {
    using Held = core::FramePrefetcher::BackgroundProgress::Held;
    std::string why;
    switch (pass.held) {
    case Held::None:
        return {};
    case Held::CacheOff:
        why = "the frame cache is off (FAULTLINE_FRAME_CACHE=0, or no cache folder)";
        break;
    case Held::CacheRefusesWrites:
        why = "the frame cache refused a frame";
        if (const auto cache = ds.frameCache(); cache && !cache->problem().empty())
            why += " (" + cache->problem() + ")";
        break;
    case Held::RunTooLarge:
        why = "the run, about " + bytesText(pass.runBytes) +
              ", is over half the frame cache's budget (" + bytesText(pass.budgetBytes) + ")";
        break;
    }
    return "Strain is not computed ahead for the other frames: " + why +
           ". Each frame's strain is computed when it is shown or prefetched.";
}

} // namespace

void StrainSection::draw(PanelContext& wb) {
    const auto& ds = wb.dataset();
    const auto& strains = wb.state().strains;
    const ViewDisplay* main = wb.mainDisplay();
    if (strains.empty())
        textWrappedAtSpaces("Shear and volumetric strain, d2min and displacement of each sphere "
                            "from how its neighbours moved: faults are where they concentrate.");
    for (std::size_t k = 0; k < strains.size(); ++k) {
        const core::StrainSpec& s = strains[k];
        ImGui::PushID(static_cast<int>(k));
        const std::string name = (s.prefix.empty() ? std::string("(no prefix)") : s.prefix + "*");
        const float removeW = buttonWidth("Remove");
        textElided(name + "  " + describe(s),
                   ImGui::GetContentRegionAvail().x - removeW - ImGui::GetStyle().ItemSpacing.x);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%sshear_strain, %svolumetric_strain, %sd2min, %sdisplacement",
                              s.prefix.c_str(), s.prefix.c_str(), s.prefix.c_str(),
                              s.prefix.c_str());
        ImGui::SameLine(ImGui::GetContentRegionMax().x - removeW);
        if (ImGui::SmallButton("Remove"))
            wb.emit(core::cmd::strainRemove(s.prefix));
        wb.mark("strain.remove." + s.prefix);
        ImGui::PopID();
    }
    // The frame on screen is still being derived (the view shows the previous one meanwhile).
    if (ds && !strains.empty() && !ds->isCached(wb.displayFrame()))
        ImGui::TextDisabled("computing strain for frame %zu...", wb.displayFrame());
    // The other frames, derived in the background for scrubbing.
    if (const auto pass = wb.frames().backgroundProgress();
        ds && !strains.empty() && pass.running && pass.total > 0) {
        const std::string label = "strain ready for " + std::to_string(pass.done) + " of " +
                                  std::to_string(pass.total) + " frames";
        ImGui::ProgressBar(float(pass.done) / float(pass.total), ImVec2(-1, 0), label.c_str());
        wb.mark("strain.progress");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Every frame's strain is computed in the background and kept in "
                              "the frame cache:\nonce done, the timeline scrubs without "
                              "computing.");
    } else if (const std::string held = ds ? heldText(pass, *ds) : std::string();
               !strains.empty() && !held.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("%s", held.c_str());
        ImGui::PopStyleColor();
        wb.mark("strain.held");
    }
    ImGui::Spacing();

    const float field = ImGui::GetFontSize() * 4;
    // Radio labels shortened in a very narrow panel (the whole on hover), not cut at the edge.
    auto radioLabel = [](const char* label) {
        const float room = ImGui::GetContentRegionAvail().x - ImGui::GetFrameHeight() -
                           ImGui::GetStyle().ItemInnerSpacing.x;
        return elided(label, room) + "###" + label;
    };
    if (ImGui::RadioButton(radioLabel("incremental").c_str(), m_incremental)) {
        m_incremental = true;
        if (!m_prefixEdited)
            m_prefix = "inc_";
    }
    wb.mark("strain.incremental");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Each frame against the frame N before it: the faults active then");
    flowSameLine(checkboxWidth("cumulative"));
    if (ImGui::RadioButton(radioLabel("cumulative").c_str(), !m_incremental)) {
        m_incremental = false;
        if (!m_prefixEdited)
            m_prefix = "";
    }
    wb.mark("strain.cumulative");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Every frame against one reference frame");
    // Labels before their fields, so the field is what a click on the item's middle hits.
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(m_incremental ? "frames before" : "since frame");
    flowSameLine(field); // a narrow panel puts fields under their labels
    if (m_incremental) {
        // Four frames before each frame, fewer in a short run: with 5 frames, 4 before would
        // leave one frame with a value.
        if (ds != m_offsetData.lock()) // other data: the default follows it again
            m_offsetData = ds, m_offsetEdited = false;
        if (!m_offsetEdited && ds)
            m_offset = std::clamp(static_cast<int>(ds->frameCount() - 1) / 8, 1, 4);
        if (numberField("##offset", &m_offset, field))
            m_offsetEdited = true;
        m_offset = std::max(1, m_offset);
        wb.mark("strain.offset");
    } else {
        numberField("##since", &m_sinceFrame, field);
        m_sinceFrame = std::max(0, m_sinceFrame);
        wb.mark("strain.since");
    }
    // The automatic cutoff, shown greyed in the empty field, which is wide enough for it
    // ("auto 0.001489" for a model in metres).
    if (!main || !main->frame) {
        m_autoFor.reset();
        m_autoText = "auto";
    } else if (m_autoFor.lock() != main->frame) {
        m_autoFor = main->frame;
        m_autoText = "auto " + numberText(core::defaultStrainCutoff(*main->frame));
    }
    const float cutoffWidth = std::max(field * 1.6f, ImGui::CalcTextSize(m_autoText.c_str()).x +
                                                         2 * ImGui::GetStyle().FramePadding.x);
    flowSameLine(ImGui::CalcTextSize("cutoff").x + ImGui::GetStyle().ItemSpacing.x + cutoffWidth);
    ImGui::TextUnformatted("cutoff");
    flowSameLine(cutoffWidth);
    numberField("##cutoff", &m_cutoff, "%.4g", cutoffWidth, m_autoText.c_str(), 0.0);
    wb.mark("strain.cutoff");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Neighbours within this distance in the reference frame\n"
                          "(empty: 1.5 x the median diameter)");
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("prefix");
    flowSameLine(field * 1.6f);
    ImGui::SetNextItemWidth(field * 1.6f);
    if (ImGui::InputText("##prefix", &m_prefix))
        m_prefixEdited = true;
    wb.mark("strain.prefix");
    flowSameLine(buttonWidth("Add"));
    ImGui::BeginDisabled(!ds);
    if (ImGui::Button("Add")) {
        core::cmd::StrainAdd cmd;
        if (m_incremental)
            cmd.sinceOffset(-m_offset);
        else
            cmd.sinceFrame(m_sinceFrame);
        if (m_cutoff > 0)
            cmd.cutoff(m_cutoff);
        if (!m_prefix.empty())
            cmd.prefix(m_prefix);
        // What was asked for, in view at once: a main view in plain colour shows the new
        // shear strain (one undo step takes both back), from its 1st to its 99th percentile in
        // the frame shown: grains that leave a model get strains hundreds of times the faults',
        // and a min-to-max range would leave every other sphere one colour.
        const core::ViewState* view = wb.state().view("main");
        if (view && view->colorVariable.empty() &&
            view->difference.mode == core::ColorDifference::Mode::None)
            wb.emit(core::cmd::batch({cmd, core::cmd::ColorSet("main")
                                               .variable(m_prefix + std::string(core::kShearStrain))
                                               .rangeMode(core::RangeMode::Percentile)}));
        else
            wb.emit(cmd);
    }
    wb.mark("strain.add");
    ImGui::EndDisabled();
}

} // namespace faultline::ui
