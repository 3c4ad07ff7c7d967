// Histograms panel: one plot per chosen variable with all spheres and the visible ones overlaid
// (log scale optional). Dragging across a plot sets that variable's threshold; its edges are
// handles; integer variables move by whole values. Chosen variables are kept with the layout.
//
// Index of this file:
// [SECTION] The panel: toolbar and plots
// [SECTION] Settings kept with the layout: variables, log scale, bins, percentile view
// [SECTION] One histogram: bins, bars, threshold drag, menu
#include "core/session/commands.hpp"
#include "ui/context/frame_columns.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/text_fit.hpp"

#include "core/model/frame_difference.hpp"
#include "core/motion/strain_spec.hpp"
#include "core/selection/histogram.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace faultline::ui {

namespace {

const ImU32 kAllColor = IM_COL32(168, 172, 180, 255);
const ImU32 kVisibleColor = IM_COL32(52, 110, 190, 255);

struct Cached {
    std::shared_ptr<const core::Frame>
        frame; // held: a pointer alone could be reused by another frame
    std::uint64_t visKey = 0;
    int autoBins = 0; // the float bin count chosen on the first frame with values, kept
    core::Histogram hist;
    // The 1st to 99th percentile of the frame's values asked for (a few extreme values, such as
    // grains thrown out of a model, left every other sphere in the first bar); whether `hist`
    // shows it (with a bin count of its own) or, the middle being one value, the whole range;
    // and the frame's smallest and largest value (what the plot's ends mean; NaN: none).
    bool middleAsked = false, middle = false, middleOneValue = false;
    int middleBins = 0;
    double fullLo = NAN, fullHi = NAN;
};

enum class DragKind { None, NewRange, Low, High };

class HistogramsPanel final : public Panel {
  public:
    const char* id() const override { return panel_ids::kHistograms; }
    const char* title() const override { return "Histograms"; }

    //-----------------------------------------------------------------------------
    // [SECTION] The panel: toolbar and plots
    //-----------------------------------------------------------------------------

    void draw(PanelContext& wb) override {
        const ViewDisplay* main = wb.mainDisplay();
        const core::Frame* frame = main && main->frame ? main->frame.get() : nullptr;
        if (wb.dataset() != m_dataset) {
            m_dataset = wb.dataset();
            m_cache.clear();
        }
        if (!frame) {
            ImGui::TextDisabled("Histograms appear when data is open.");
            return;
        }
        std::vector<std::string> vars = chosenVariables(wb, *frame);
        bool logScale = settingsLog(wb);

        // Toolbar: add a variable, log scale.
        // The combo as wide as its text (the arrow beside it); "Log scale" flows on when narrow.
        const ImGuiStyle& style = ImGui::GetStyle();
        ImGui::SetNextItemWidth(std::min(ImGui::GetContentRegionAvail().x,
                                         ImGui::CalcTextSize("Add a histogram...").x +
                                             ImGui::GetFrameHeight() + 2 * style.FramePadding.x));
        const std::string addLabel =
            elided("Add a histogram...",
                   ImGui::CalcItemWidth() - ImGui::GetFrameHeight() - 2 * style.FramePadding.x);
        if (ImGui::BeginCombo("##addhist", addLabel.c_str())) {
            for (const auto& [v, info] : wb.columns().of(main->frame))
                if (std::find(vars.begin(), vars.end(), v) == vars.end() &&
                    ImGui::Selectable(v.c_str())) {
                    vars.push_back(v);
                    saveSettings(wb, vars, logScale);
                }
            ImGui::EndCombo();
        }
        wb.mark("histograms.add");
        flowSameLine(checkboxWidth("Log scale"));
        if (ImGui::Checkbox("Log scale", &logScale))
            saveSettings(wb, vars, logScale);
        wb.mark("histograms.log");
        const float legendW =
            ImGui::CalcTextSize("allvisible").x + ImGui::GetTextLineHeight() * 2 + 30 * wb.scale();
        const float usedX = ImGui::GetItemRectMax().x - ImGui::GetWindowPos().x;
        if (ImGui::GetContentRegionMax().x - usedX > legendW + 10 * wb.scale())
            ImGui::SameLine(ImGui::GetContentRegionMax().x - legendW);
        legendSwatch(kAllColor, "all");
        ImGui::SameLine();
        legendSwatch(kVisibleColor, "visible");

        std::string removeVar;
        for (const std::string& v : vars) {
            ImGui::PushID(v.c_str());
            ImGui::Spacing();
            if (!drawOne(wb, *frame, *main, v, logScale))
                removeVar = v;
            ImGui::PopID();
        }
        if (!removeVar.empty()) {
            std::erase(vars, removeVar);
            saveSettings(wb, vars, logScale);
        }
    }

  private:
    static void legendSwatch(ImU32 color, const char* label) {
        const float h = ImGui::GetTextLineHeight();
        const ImVec2 p = ImGui::GetCursorScreenPos();
        const float y = p.y + ImGui::GetStyle().FramePadding.y;
        ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, y + h * 0.2f),
                                                  ImVec2(p.x + h * 0.8f, y + h), color, 2);
        ImGui::Dummy(ImVec2(h * 0.8f, ImGui::GetFrameHeight()));
        ImGui::SameLine(0, 4);
        ImGui::AlignTextToFramePadding();
        ImGui::TextDisabled("%s", label);
    }

    //-----------------------------------------------------------------------------
    // [SECTION] Settings kept with the layout: variables, log scale, bins, percentile view
    //-----------------------------------------------------------------------------

    std::vector<std::string> chosenVariables(PanelContext& wb, const core::Frame& frame) {
        const core::Json* s = std::as_const(wb.layout()).panelSettings(panel_ids::kHistograms);
        std::vector<std::string> out;
        if (s && s->contains("variables") && (*s)["variables"].is_array()) {
            for (const auto& v : (*s)["variables"])
                if (v.is_string())
                    out.push_back(v.get<std::string>());
            return out;
        }
        // Default: the shear strain of each strain from motion, then the file's first columns in
        // its order, three in all: the same list whatever the colouring and however the session
        // was reached (issue 41: the order changed after reopening a session, which took the
        // colour variable first). Chosen again when the columns change (strain from motion added
        // or taken away): its shear strain shows once derived, and again after it is derived
        // anew.
        std::vector<std::string> names = frame.attributeNames();
        if (wb.dataset().get() == m_defaultFor && !m_default.empty() && names == m_defaultNames)
            return m_default;
        // (A file with velocities or types of its own showed those alone after Add.)
        for (const core::StrainSpec& spec : wb.state().strains) {
            const std::string shear = spec.variable(core::kShearStrain);
            if (out.size() < 3 && std::find(names.begin(), names.end(), shear) != names.end() &&
                std::find(out.begin(), out.end(), shear) == out.end())
                out.push_back(shear);
        }
        for (const std::string& n : names) {
            if (out.size() >= 3)
                break;
            if (std::find(out.begin(), out.end(), n) == out.end())
                out.push_back(n);
        }
        if (out.empty())
            out.push_back("radius");
        m_default = out;
        m_defaultFor = wb.dataset().get();
        m_defaultNames = std::move(names);
        return out;
    }
    std::vector<std::string> m_default; // the default list, and the dataset it was chosen for
    const void* m_defaultFor = nullptr;
    std::vector<std::string> m_defaultNames; // the frame's columns it was chosen from

    static bool settingsLog(PanelContext& wb) {
        // Log by default: DEM variables (broken bonds, strain) are strongly skewed.
        const core::Json* s = std::as_const(wb.layout()).panelSettings(panel_ids::kHistograms);
        return !(s && s->contains("log") && (*s)["log"].is_boolean()) || (*s)["log"].get<bool>();
    }

    static void saveSettings(PanelContext& wb, const std::vector<std::string>& vars, bool log) {
        core::Json& s = wb.layout().panelSettings(panel_ids::kHistograms);
        s["variables"] = vars;
        s["log"] = log;
        wb.commitLayout();
    }

    // A float variable's automatic bin count is chosen on the first frame it has values at and
    // kept while scrubbing; it rides along in the panel's settings (saved with the session,
    // without marking it changed), so a reopened session shows the same bins rather than
    // those of the frame it reopens at.
    static int savedBins(PanelContext& wb, const std::string& var) {
        const core::Json* s = std::as_const(wb.layout()).panelSettings(panel_ids::kHistograms);
        if (!s || !s->contains("bins") || !(*s)["bins"].is_object())
            return 0;
        const core::Json& bins = (*s)["bins"];
        const auto it = bins.find(var);
        // One bin: chosen on a frame with one value or none (sessions saved before the count
        // waited for values); chosen again.
        return it != bins.end() && it->is_number_integer() && it->get<int>() > 1 &&
                       it->get<int>() <= core::kMaxAutoHistogramBins
                   ? it->get<int>()
                   : 0;
    }

    // Whether a variable's plot shows the middle 98 % of its values (kept with the layout).
    static bool savedMiddle(PanelContext& wb, const std::string& var) {
        const core::Json* s = std::as_const(wb.layout()).panelSettings(panel_ids::kHistograms);
        if (!s || !s->contains("middle") || !(*s)["middle"].is_object())
            return false;
        const auto it = (*s)["middle"].find(var);
        return it != (*s)["middle"].end() && it->is_boolean() && it->get<bool>();
    }
    static void saveMiddle(PanelContext& wb, const std::string& var, bool middle) {
        core::Json& s = wb.layout().panelSettings(panel_ids::kHistograms);
        if (middle)
            s["middle"][var] = true;
        else if (s.contains("middle") && s["middle"].is_object())
            s["middle"].erase(var);
        wb.commitLayout();
    }

    //-----------------------------------------------------------------------------
    // [SECTION] One histogram: bins, bars, threshold drag, menu
    //-----------------------------------------------------------------------------

    const core::Histogram* histogramFor(PanelContext& wb, const core::Frame& frame,
                                        const ViewDisplay& main, const std::string& var) {
        Cached& c = m_cache[var];
        if (c.autoBins == 0)
            c.autoBins = savedBins(wb, var);
        const std::uint64_t visKey = main.visibilityKey;
        const bool asked = savedMiddle(wb, var);
        const bool sameFrame =
            c.frame.get() == &frame && !c.hist.edges.empty() && c.middleAsked == asked;
        if (sameFrame && c.visKey == visKey)
            return &c.hist;
        auto column = core::findColumn(frame, var);
        if (!column)
            return nullptr;
        try {
            const auto* mask = main.visibility ? &main.visibility->mask : nullptr;
            // Only the visible spheres changed (a threshold or box dragged): the same bins,
            // counted again.
            if (sameFrame) {
                c.hist = core::computeHistogram(*column, c.hist.binning, mask);
                c.visKey = visKey;
                return &c.hist;
            }
            c.frame = main.frame;
            c.visKey = visKey;
            c.middleAsked = asked;
            c.middle = c.middleOneValue = false;
            c.fullLo = c.fullHi = NAN;
            if (const auto full = core::variableRange(frame, var))
                c.fullLo = full->low, c.fullHi = full->high;
            if (asked && !column->isInteger()) {
                // The middle 98 % of this frame's values, in bins of their own (chosen once); the
                // percentiles of at most 65,536 evenly spaced rows (a display range: scrubbing
                // millions of spheres, each new frame sorted them all on the UI thread).
                std::vector<std::uint8_t> sampled(frame.size(), 0);
                const std::size_t step = std::max<std::size_t>(1, frame.size() / 65536);
                for (std::size_t row = 0; row < frame.size(); row += step)
                    sampled[row] = 1;
                const auto q = core::maskedQuantiles(frame, var, sampled, 0.01, 0.99);
                if (q && q->first < q->second) {
                    core::HistogramSpec spec;
                    spec.range = std::array<double, 2>{q->first, q->second};
                    spec.bins = c.middleBins;
                    const core::HistogramBinning b = core::chooseBinning(*column, spec);
                    c.middleBins = b.bins;
                    c.hist = core::computeHistogram(*column, b, mask);
                    c.middle = true;
                    return &c.hist;
                }
                c.middleOneValue = q.has_value(); // the whole range is shown, and says why
            }
            core::HistogramSpec spec;
            if (c.autoBins > 0 && !column->isInteger())
                spec.bins = c.autoBins;
            const core::HistogramBinning binning = core::chooseBinning(*column, spec);
            c.hist = core::computeHistogram(*column, binning, mask);
            // The bin count is kept (the bars hold still while frames change) once it comes from
            // values: a frame where every value is NaN (incremental strain on the first frames)
            // gave one bin, kept for every frame after and saved with the layout.
            if (!column->isInteger() && c.autoBins == 0 && c.hist.all.inRange() > 0 &&
                binning.bins > 1) {
                c.autoBins = binning.bins;
                wb.layout().panelSettings(panel_ids::kHistograms)["bins"][var] = binning.bins;
            }
            return &c.hist;
        } catch (const std::exception&) {
            return nullptr;
        }
    }

    // Draws one histogram; false when its close button was pressed.
    bool drawOne(PanelContext& wb, const core::Frame& frame, const ViewDisplay& main,
                 const std::string& var, bool logScale) {
        const float scale = wb.scale();
        const core::Histogram* h = histogramFor(wb, frame, main, var);
        const auto info = wb.columns().info(main.frame, var);
        const core::VariableThreshold* t = wb.state().threshold(var);

        // Title line: name, threshold, close.
        // The name and threshold shortened to leave the close button its place.
        const float closeW = ImGui::GetFrameHeight();
        const float room =
            ImGui::GetContentRegionAvail().x - closeW - ImGui::GetStyle().ItemSpacing.x;
        ImGui::AlignTextToFramePadding();
        textElided(var, room);
        if (t) {
            ImGui::SameLine();
            const std::string text = std::string(t->enabled ? "threshold" : "threshold (off)") +
                                     "  " + numberText(t->low) + " .. " + numberText(t->high);
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            textElided(text,
                       std::max(0.0f, ImGui::GetWindowContentRegionMax().x +
                                          ImGui::GetWindowPos().x - ImGui::GetCursorScreenPos().x -
                                          closeW - ImGui::GetStyle().ItemSpacing.x));
            ImGui::PopStyleColor();
        }
        ImGui::SameLine(ImGui::GetContentRegionMax().x - closeW);
        const bool keep = !ImGui::Button("x", ImVec2(closeW, 0));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Hide this histogram");
        if (!h || !info) {
            ImGui::TextDisabled("(%s is not in this frame)", var.c_str());
            return keep;
        }

        const float width = ImGui::GetContentRegionAvail().x;
        const float height = std::round(96 * scale);
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        ImGui::InvisibleButton("##plot", ImVec2(std::max(width, 10.0f), height));
        wb.mark("histogram." + var);
        const bool hovered = ImGui::IsItemHovered();
        ImDrawList* dl = ImGui::GetWindowDrawList();
        const ImVec2 p1(p0.x + width, p0.y + height);
        dl->AddRectFilled(p0, p1, ImGui::GetColorU32(ImGuiCol_FrameBg), 3 * scale);

        const double lo = h->binning.lo, hi = h->edges.back();
        const bool integer = h->binning.isInteger();
        auto toX = [&](double v) {
            return p0.x + static_cast<float>((std::clamp(v, lo, hi) - lo) / (hi - lo)) * width;
        };
        // Within a few pixels of either end means the end itself (the range's min or max; the
        // values' own min or max when the plot shows their middle: a threshold dragged to the
        // right end takes the extreme values too).
        const Cached& cached = m_cache[var];
        const bool middle = cached.middle;
        const double endLo =
            middle && std::isfinite(cached.fullLo) ? std::min(lo, cached.fullLo) : lo;
        const double endHi =
            middle && std::isfinite(cached.fullHi) ? std::max(hi, cached.fullHi) : hi;
        auto valueAt = [&](float x) {
            return lo + (std::clamp(x, p0.x, p1.x) - p0.x) / width * (hi - lo);
        };
        auto toValue = [&](float x) {
            if (x <= p0.x + 3 * scale)
                return endLo;
            if (x >= p1.x - 3 * scale)
                return endHi;
            return valueAt(x);
        };

        // Bars: all, then visible over them.
        const std::uint64_t maxAll = std::max<std::uint64_t>(1, h->all.maxBin());
        auto barH = [&](std::uint64_t c) {
            const double f =
                logScale ? std::log10(1.0 + c) / std::log10(1.0 + maxAll) : double(c) / maxAll;
            return static_cast<float>(f) * (height - 4 * scale);
        };
        const std::size_t bins = h->all.bins.size();
        for (std::size_t k = 0; k < bins; ++k) {
            float x0 = toX(h->edges[k]), x1 = toX(h->edges[k + 1]);
            if (x1 - x0 > 3)
                x1 -= 1; // a hairline gap between wide bars
            const std::uint64_t a = h->all.bins[k];
            if (a)
                dl->AddRectFilled(ImVec2(x0, p1.y - barH(a)), ImVec2(std::max(x1, x0 + 1), p1.y),
                                  kAllColor);
            if (h->hasVisible && h->visible.bins[k])
                dl->AddRectFilled(ImVec2(x0, p1.y - barH(h->visible.bins[k])),
                                  ImVec2(std::max(x1, x0 + 1), p1.y), kVisibleColor);
        }

        // Threshold band and handles (the drag's values while dragging).
        Drag& d = m_drag[var];
        std::optional<std::array<double, 2>> band;
        if (d.kind != DragKind::None)
            band = std::array<double, 2>{d.low, d.high};
        else if (t)
            band = std::array<double, 2>{t->low, t->high};
        auto edgeX = [&](double v, bool isHigh) { return toX(integer && isHigh ? v + 1 : v); };
        float bx0 = 0, bx1 = 0;
        if (band) {
            bx0 = edgeX((*band)[0], false);
            bx1 = edgeX((*band)[1], true);
            const bool off = t && !t->enabled && d.kind == DragKind::None;
            const ImU32 shade = off ? IM_COL32(120, 120, 120, 30) : IM_COL32(52, 110, 190, 34);
            dl->AddRectFilled(ImVec2(bx0, p0.y), ImVec2(bx1, p1.y), shade);
            const ImU32 edge = off ? IM_COL32(120, 120, 120, 160) : IM_COL32(200, 90, 20, 255);
            for (float x : {bx0, bx1}) {
                dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), edge, 2 * scale);
                dl->AddRectFilled(ImVec2(x - 4 * scale, p0.y),
                                  ImVec2(x + 4 * scale, p0.y + 10 * scale), edge, 2 * scale);
            }
        }

        // Interaction.
        const ImGuiIO& io = ImGui::GetIO();
        const float grab = 6 * scale;
        if (hovered && band &&
            (std::fabs(io.MousePos.x - bx0) < grab || std::fabs(io.MousePos.x - bx1) < grab))
            ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
        if (ImGui::IsItemActivated()) {
            const float mx = io.MousePos.x;
            d.anchor = toValue(mx);
            if (band && std::fabs(mx - bx0) < grab && std::fabs(mx - bx0) <= std::fabs(mx - bx1))
                d.kind = DragKind::Low;
            else if (band && std::fabs(mx - bx1) < grab)
                d.kind = DragKind::High;
            else
                d.kind = DragKind::NewRange;
            d.low = band ? (*band)[0] : lo;
            d.high = band ? (*band)[1] : hi;
            d.moved = false;
            d.startX = mx;
        }
        if (ImGui::IsItemActive() && d.kind != DragKind::None) {
            const double v = toValue(io.MousePos.x);
            if (std::fabs(io.MousePos.x - d.startX) > 2 * scale)
                d.moved = true;
            if (d.moved) {
                if (d.kind == DragKind::NewRange) {
                    double a = std::min(d.anchor, v), b = std::max(d.anchor, v);
                    if (integer) {
                        a = std::floor(a);
                        b = std::min(std::floor(b), hi - 1);
                    }
                    d.low = a, d.high = b;
                } else if (d.kind == DragKind::Low) {
                    d.low = integer ? std::round(v) : v;
                    d.low = std::min(d.low, d.high);
                } else {
                    d.high = integer ? std::round(v) - 1 : v;
                    d.high = std::max(d.high, d.low);
                }
                if (!integer) {
                    const double step = (hi - lo) / 1000.0; // a readable precision
                    if (d.low > endLo)
                        d.low = std::max(endLo, std::floor(d.low / step) * step);
                    if (d.high < endHi)
                        d.high = std::min(endHi, std::ceil(d.high / step) * step);
                    if (d.low <= endLo)
                        d.low = endLo;
                }
                wb.preview("histogram." + var, command(t, var, d));
            }
        }
        if (ImGui::IsItemDeactivated() && d.kind != DragKind::None) {
            if (d.moved)
                wb.emit(command(t, var, d));
            d.kind = DragKind::None;
        }
        if (ImGui::BeginPopupContextItem("##histmenu")) {
            if (t && ImGui::MenuItem(t->enabled ? "Disable the threshold" : "Enable the threshold"))
                wb.emit(core::cmd::ThresholdSet(var).enabled(!t->enabled));
            if (t && ImGui::MenuItem("Remove the threshold"))
                wb.emit(core::cmd::thresholdRemove(var));
            if (!t)
                ImGui::TextDisabled("Drag across the plot to set a threshold.");
            if (!integer) {
                ImGui::Separator();
                if (ImGui::MenuItem("Show the 1st to 99th percentile", nullptr, middle))
                    saveMiddle(wb, var, !middle);
                wb.mark("histogram." + var + ".middle");
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("A few extreme values (grains thrown out of the model) leave "
                                      "every other sphere in the first bar:\nshow the middle "
                                      "98 %% of the values, and how many lie beyond.");
            }
            ImGui::EndPopup();
        }
        if (hovered && d.kind == DragKind::None) {
            if (auto bin =
                    h->binning.binOf(std::min(valueAt(io.MousePos.x), std::nextafter(hi, lo)))) {
                const std::size_t k = static_cast<std::size_t>(*bin);
                ImGui::BeginTooltip();
                if (integer && h->binning.integerWidth == 1)
                    ImGui::Text("%s = %s", var.c_str(), numberText(h->edges[k]).c_str());
                else
                    ImGui::Text("%s in [%s, %s)", var.c_str(), numberText(h->edges[k]).c_str(),
                                numberText(h->edges[k + 1]).c_str());
                ImGui::Text("%llu spheres, %llu visible",
                            static_cast<unsigned long long>(h->all.bins[k]),
                            static_cast<unsigned long long>(h->hasVisible ? h->visible.bins[k]
                                                                          : h->all.bins[k]));
                // Right-click: the threshold's switches once there is one, the percentile view
                // on a float variable.
                ImGui::TextDisabled(
                    "%s", t ? "drag to set the threshold; right-click to disable or remove it"
                          : integer ? "drag across the plot to set a threshold"
                                    : "drag across the plot to set a threshold; right-click to "
                                      "show the 1st to 99th percentile");
                ImGui::EndTooltip();
            }
        }
        // Axis: range ends under the plot.
        const std::string left = numberText(lo), right = numberText(integer ? hi - 1 : hi);
        ImGui::TextDisabled("%s", left.c_str());
        ImGui::SameLine(std::max(ImGui::GetCursorPosX(), ImGui::GetContentRegionMax().x -
                                                             ImGui::CalcTextSize(right.c_str()).x));
        ImGui::TextDisabled("%s", right.c_str());
        if (middle && h->all.outside > 0) {
            hint("1st to 99th percentile; %llu sphere%s beyond",
                 static_cast<unsigned long long>(h->all.outside), h->all.outside == 1 ? "" : "s");
            wb.mark("histogram." + var + ".beyond");
        } else if (cached.middleOneValue) {
            hint("The middle 98 %% of the values are one value: all are shown");
        } else if (!middle && !integer && core::extremesStretchAxis(*h)) {
            // A few extreme values (grains thrown out of the model, with strains in the tens)
            // set the range: the menu's middle view, offered here (not for a long tail that
            // holds more: the demo's strain, whose top 1 % spans 71 % of the axis).
            hint("98 %% of the values fill under a fifth of the axis.");
            flowSameLine(buttonWidth("1st to 99th percentile"));
            if (ImGui::SmallButton("1st to 99th percentile"))
                saveMiddle(wb, var, true);
            wb.mark("histogram." + var + ".offer-middle");
        }
        // NaN (no reference for strain from motion, a sphere gone since it): never passes a
        // threshold, so say how many there are.
        if (h->all.nan > 0) {
            hint("%llu sphere%s without a value (pass no threshold)",
                 static_cast<unsigned long long>(h->all.nan), h->all.nan == 1 ? "" : "s");
            wb.mark("histogram." + var + ".nan");
        }
        return keep;
    }

    struct Drag {
        DragKind kind = DragKind::None;
        double anchor = 0, low = 0, high = 0;
        float startX = 0;
        bool moved = false;
    };

    static core::Json command(const core::VariableThreshold* t, const std::string& var,
                              const Drag& d) {
        if (!t)
            return core::cmd::ThresholdAdd(var).low(d.low).high(d.high);
        core::cmd::ThresholdSet cmd(var);
        cmd.low(d.low).high(d.high);
        if (!t->enabled)
            cmd.enabled(true); // dragging a threshold means using it
        return cmd;
    }

    std::shared_ptr<core::Dataset> m_dataset;
    std::map<std::string, Cached> m_cache;
    std::map<std::string, Drag> m_drag;
};

} // namespace

std::unique_ptr<Panel> makeHistogramsPanel() { return std::make_unique<HistogramsPanel>(); }

} // namespace faultline::ui
