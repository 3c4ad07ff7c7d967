// "Metrics over time" in the Faults panel: a metric of the selected faults (all faults when none
// is selected) over every frame, from a background job, with the current frame as a cursor;
// clicking or dragging on the plot goes to that frame like the timeline does.
#include "core/faults/metric_fields.hpp"
#include "core/faults/tracking.hpp"
#include "core/selection/column_view.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/commands.hpp"
#include "core/session/session.hpp"
#include "ui/context/fault_metrics_cache.hpp"
#include "ui/panels/panels.hpp"
#include "ui/widgets/section.hpp"
#include "ui/widgets/series_plot.hpp"
#include "ui/widgets/text_fit.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

namespace faultline::ui {

namespace {

constexpr std::size_t kMaxLines = 12; // more lines than this are unreadable anyway

ImU32 colorOf(const core::Fault& f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(f.color[0], f.color[1], f.color[2], 1.0f));
}

// What these faults, followed as candidates of the visible spheres frame by frame, and this
// selection of visible spheres make as a key: events found for another key are not shown.
std::string eventsKey(const core::SessionState& s, std::span<const core::Fault* const> faults,
                      const void* dataset) {
    std::string key = std::to_string(reinterpret_cast<std::uintptr_t>(dataset));
    char buf[160];
    for (const core::Fault* f : faults)
        key += "|f" + f->name + ":" + std::to_string(core::hashMemberIds(f->ids));
    for (const auto& b : s.boxes) {
        std::snprintf(buf, sizeof buf, "|b%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d", b.min[0], b.min[1],
                      b.min[2], b.max[0], b.max[1], b.max[2], int(b.mode), int(b.enabled));
        key += buf;
    }
    for (const auto& t : s.thresholds) {
        std::snprintf(buf, sizeof buf, "|t%.9g,%.9g,%d,", t.low, t.high, int(t.enabled));
        key += buf + t.variable;
    }
    key += "|filter" + std::to_string(int(s.faultFilter.mode)) + s.faultFilter.fault;
    return key;
}

// What the visible spheres of every frame depend on: the data, boxes, thresholds, and the
// faults only when the fault filter or a hidden fault takes spheres out.
std::string visibleKey(const core::SessionState& s, const void* dataset) {
    std::string key = eventsKey(s, {}, dataset);
    const bool rowsMasked = s.faultFilter.mode != core::FaultFilter::Mode::All ||
                            std::any_of(s.faults.begin(), s.faults.end(),
                                        [](const core::Fault& f) { return !f.visible; });
    if (rowsMasked)
        for (const auto& f : s.faults)
            key += "|m" + std::to_string(core::hashMemberIds(f.ids)) + (f.visible ? "v" : "h");
    return key;
}

// Each frame's candidates of the visible spheres, kept while what the spheres shown depend on
// stays the same (issue 41: following other faults searched every frame again, 12-15 s on the
// demo). Shared with the background jobs; at most kBudget bytes, past which frames are searched
// again when needed.
struct CandidateMemo {
    static constexpr std::size_t kBudget = std::size_t(512) << 20;
    std::string key;
    std::mutex mutex;
    std::map<std::size_t, std::shared_ptr<const core::CandidateSet>> frames;
    std::size_t bytes = 0;

    static std::size_t sizeOf(const core::CandidateSet& set) {
        std::size_t b = set.rowLabel.size() * sizeof(std::int32_t);
        for (const auto& c : set.candidates)
            b += c.ids.size() * sizeof(std::int64_t);
        return b;
    }
};

// The selection per-frame results ran with, in words: "thresholds broken_bonds 3 .. max;
// boxes north (keep)" (issue 41: events changed with the thresholds without a word).
std::string conditionsText(const core::SessionState& s) {
    std::string thresholds, boxes;
    char buf[96];
    for (const auto& t : s.thresholds)
        if (t.enabled) {
            char low[32], high[32]; // open ends in words, as the Thresholds panel says them
            std::snprintf(low, sizeof low, "%.4g", t.low);
            std::snprintf(high, sizeof high, "%.4g", t.high);
            std::snprintf(buf, sizeof buf, " %s .. %s", t.low <= -1e29 ? "min" : low,
                          t.high >= 1e29 ? "max" : high);
            thresholds += (thresholds.empty() ? "" : ", ") + t.variable + buf;
        }
    for (const auto& b : s.boxes)
        if (b.enabled)
            boxes += (boxes.empty() ? "" : ", ") + b.name +
                     (b.mode == core::BoxMode::Keep ? " (keep)" : " (cut)");
    return "thresholds: " + (thresholds.empty() ? std::string("none") : thresholds) +
           "; boxes: " + (boxes.empty() ? std::string("none") : boxes);
}

// Thresholds on variables the data lacks select nothing (issue 41, item 13): said beside the
// conditions the faults were followed with, so they do not read as applied.
std::string ignoredThresholds(const core::SessionState& s, const core::Frame* frame) {
    std::string out;
    if (!frame)
        return out;
    for (const auto& t : s.thresholds)
        if (t.enabled && !core::missingVariableNote(*frame, t.variable).empty())
            out += (out.empty() ? "" : ", ") + t.variable;
    return out.empty() ? out : " (ignored, not in this data: " + out + ")";
}

class FaultMetricsSection {
  public:
    void draw(PanelContext& wb) {
        const core::SessionState& s = wb.state();
        auto ds = wb.dataset();
        if (!ds) {
            hint("Open data to follow the faults' metrics over time.");
            return;
        }
        if (s.faults.empty()) {
            ImGui::TextDisabled("No faults yet.");
            return;
        }
        // The faults on show, in table order.
        std::vector<const core::Fault*> shown;
        for (const auto& f : s.faults)
            if (wb.selection().faults.empty() || wb.selection().faults.count(f.name))
                shown.push_back(&f);
        const bool all = wb.selection().faults.empty();
        const std::size_t total = shown.size();
        if (shown.size() > kMaxLines)
            shown.resize(kMaxLines);
        m_cache.request(wb.jobs(), wb.now(), ds, shown);

        // The metric.
        const auto fields = core::metricFields();
        m_metric = std::min(m_metric, fields.size() - 1);
        const core::MetricField& field = fields[m_metric];
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted("Metric");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(std::min(ImGui::GetContentRegionAvail().x, 260 * wb.scale()));
        if (ImGui::BeginCombo("##metric", std::string(field.label).c_str())) {
            for (std::size_t k = 0; k < fields.size(); ++k) {
                if (ImGui::Selectable(std::string(fields[k].label).c_str(), k == m_metric))
                    m_metric = k;
                wb.mark("faults.metrics.metric." + std::string(fields[k].key));
            }
            ImGui::EndCombo();
        }
        wb.mark("faults.metrics.metric");
        if (all && total > shown.size())
            hint("first %zu of %zu faults", shown.size(), total);
        else if (all && total == 1)
            hint("the one fault");
        else if (all)
            hint("all %zu faults", shown.size());
        else
            hint("%zu selected", shown.size());

        // The values of each fault, and what is still being computed.
        m_values.assign(shown.size(), {});
        std::vector<PlotLine> lines;
        std::size_t pending = 0, unformed = 0;
        for (std::size_t k = 0; k < shown.size(); ++k) {
            auto series = m_cache.find(ds, *shown[k]);
            if (!series) {
                ++pending;
                continue;
            }
            // Issue 41: the fixed members exist before their fault formed; the line starts at
            // the frame where the first of their bonds broke (when the data counts broken bonds).
            const std::size_t formed = series->formedFrom();
            for (std::size_t f = 0; f < series->frames.size(); ++f)
                m_values[k].push_back(f < formed ? std::numeric_limits<double>::quiet_NaN()
                                                 : field.value(series->frames[f]));
            if (formed > 0)
                ++unformed;
            lines.push_back({shown[k]->name, m_values[k], colorOf(*shown[k])});
        }
        if (pending > 0) {
            const float p = m_cache.progress();
            char text[96];
            std::snprintf(text, sizeof text, "computing %zu fault%s over %zu frames...", pending,
                          pending == 1 ? "" : "s", ds->frameCount());
            if (m_cache.computing()) {
                ImGui::ProgressBar(std::max(0.0f, p), ImVec2(-1, 0), text);
                wb.mark("faults.metrics.progress");
            } else if (!m_cache.lastError().empty()) {
                if (ImGui::Button("Compute again"))
                    m_cache.retry();
                wb.mark("faults.metrics.retry");
                ImGui::SameLine();
                ImGui::TextColored(ImVec4(0.8f, 0.16f, 0.12f, 1), "Metrics %s%s",
                                   m_cache.lastError() == "cancelled" ? "" : "failed: ",
                                   m_cache.lastError().c_str());
            }
        }

        // Events: when the faults, followed as candidates of the visible spheres, appeared,
        // linked and split (as export.csv fault_events), marked on the plot.
        const std::string key = eventsKey(s, shown, ds.get());
        const bool finding = m_eventsJob && !m_eventsJob->finished();
        ImGui::BeginDisabled(finding);
        if (ImGui::Button(finding ? "Following..." : "Follow through time")) {
            m_followAgain = true;
            findEvents(wb, ds, shown, key);
        }
        ImGui::EndDisabled();
        wb.mark("faults.metrics.events");
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip(
                "Follow these faults as candidates of the visible spheres through every frame:\n"
                "marks A appeared, L linked (two faults become one), S split; Growth plots\n"
                "the metric of what each fault is in each frame");
        std::vector<PlotMark> marks;
        // Followed before with other thresholds or boxes: followed again, and said so.
        if (m_events && m_events->key != key && m_followAgain &&
            !(m_eventsJob && !m_eventsJob->finished())) {
            // Said here, not in the status bar: there it would hide what changed the faults
            // ("Moved 285 from Graben W to C1", walkthrough of issue 41).
            m_followReason = m_events->conditions != conditionsText(s)
                                 ? "Thresholds or boxes changed: following the faults again..."
                                 : "The faults changed: following them again...";
            findEvents(wb, ds, shown, key);
        }
        const bool followed = m_events && m_events->key == key;
        if (m_events && !followed) {
            hint(m_followReason.empty() ? "Following again..." : m_followReason.c_str());
            wb.mark("faults.metrics.following_again");
        }
        if (followed) {
            flowSameLine(checkboxWidth("Growth"));
            ImGui::Checkbox("Growth", &m_growth);
            wb.mark("faults.metrics.growth");
            flowSameLine(ImGui::CalcTextSize("00 events").x);
            ImGui::TextDisabled("%zu event%s", m_events->count, m_events->count == 1 ? "" : "s");
            wb.mark("faults.metrics.events.shown");
            marks = m_events->marks;
            const ViewDisplay* main = wb.mainDisplay();
            hint("%s", ("with " + m_events->conditions +
                        ignoredThresholds(s, main ? main->frame.get() : nullptr))
                           .c_str());
            // Every event, named (a mark on the plot may stand for several).
            // The first few events in words, the rest behind a toggle (a walkthrough: 46 lines
            // pushed the plot a screen down); the plot's tooltip names each frame's events.
            constexpr std::size_t kListed = 6;
            const std::size_t listed =
                m_allEvents ? m_events->marks.size() : std::min(kListed, m_events->marks.size());
            for (std::size_t k = 0; k < listed; ++k) {
                const PlotMark& m = m_events->marks[k];
                hint("%s", ("frame " + std::to_string(m.frame) + ": " + m.text).c_str());
            }
            if (m_events->marks.size() > kListed) {
                char more[64];
                std::snprintf(more, sizeof more, m_allEvents ? "fewer##events" : "%zu more##events",
                              m_events->marks.size() - kListed);
                if (ImGui::SmallButton(more))
                    m_allEvents = !m_allEvents;
                wb.mark("faults.metrics.events.more");
            }
            if (m_growth) { // the lines follow the candidates instead of the fixed members
                const core::FaultMetricsSeries& g = m_events->growth;
                lines.clear();
                for (std::size_t k = 0; k < shown.size() && k < g.faultCount; ++k) {
                    m_values[k].clear();
                    for (std::size_t f = 0; f < g.frameCount; ++f)
                        m_values[k].push_back(field.value(g.at(f, k)));
                    lines.push_back({shown[k]->name, m_values[k], colorOf(*shown[k])});
                }
            }
        }

        // The plot: as tall as the panel allows, but legible.
        const float scale = wb.scale();
        const float below =
            static_cast<float>(shown.size() + 1) * ImGui::GetTextLineHeightWithSpacing();
        const float h = std::clamp(ImGui::GetContentRegionAvail().y - below - 4 * scale,
                                   150 * scale, 300 * scale);
        const std::size_t cursor = wb.displayFrame();
        const PlotInput in =
            seriesPlot("##metricplot", lines, ds->frameCount(), m_scrub.value_or(cursor),
                       ImVec2(std::max(80.0f, ImGui::GetContentRegionAvail().x), h), field.integer,
                       scale, marks);
        wb.mark("faults.metrics.plot");
        if (in.frame && !in.released) {
            m_scrub = in.frame;
            if (wb.playback().playing)
                wb.playback().frame = *in.frame;
            else
                wb.preview("faults.metrics.scrub", core::cmd::frameSet(*in.frame));
        }
        if (in.released) {
            if (in.frame && !wb.playback().playing)
                wb.jumpToFrame(static_cast<long long>(*in.frame));
            m_scrub.reset();
        }
        if (unformed > 0 && !(m_events && m_events->key == key && m_growth)) {
            hint("Each line starts where its fault's first bonds broke");
            wb.mark("faults.metrics.from_formed");
        }
        drawRanges(wb, shown);
        if (m_cache.lastSeconds() > 0 && pending == 0)
            hint("%s%s%s; computed over %zu frames in %.2f s", std::string(field.label).c_str(),
                 field.unit.empty() ? "" : " in ", std::string(field.unit).c_str(),
                 m_cache.lastFrameCount(), m_cache.lastSeconds());
    }

  private:
    struct Events {
        std::string key;
        std::vector<PlotMark> marks;     // one per frame and kind
        std::size_t count = 0;           // events
        core::FaultMetricsSeries growth; // metrics of each fault's candidate, frame by frame
        std::string conditions;          // the thresholds and boxes they ran with
    };
    bool m_growth = false;
    bool m_allEvents = false;   // every event listed, not only the first few
    bool m_followAgain = false; // the user followed once: follow again when the selection changes
    std::string m_followReason; // why the faults are being followed again (shown in the panel)
    std::optional<Events> m_events;
    std::shared_ptr<Job> m_eventsJob;
    std::shared_ptr<CandidateMemo> m_memo;

    // Tracks of the faults over every frame (candidates as fault.candidates' defaults, of the
    // visible spheres as the session's boxes, thresholds and fault filter say), in the
    // background; their events become the plot's marks.
    void findEvents(PanelContext& wb, const std::shared_ptr<core::Dataset>& ds,
                    std::span<const core::Fault* const> shown, const std::string& key) {
        std::vector<core::Fault> faults;
        for (const core::Fault* f : shown)
            faults.push_back(*f);
        const std::string memoKey = visibleKey(wb.state(), ds.get());
        if (!m_memo || m_memo->key != memoKey) { // a job still running keeps its own
            m_memo = std::make_shared<CandidateMemo>();
            m_memo->key = memoKey;
        }
        m_eventsJob = wb.jobs().start(
            "Finding fault links and splits",
            [this, ds, faults = std::move(faults), state = wb.state(), key,
             memo = m_memo](JobControl& control) -> std::function<void()> {
                core::CandidateOptions options;
                options.minSize = core::kDefaultCandidateMinSize;
                const std::size_t frames = ds->frameCount();
                std::vector<core::FaultTrack> tracks;
                const core::CandidatesFn search = core::candidatesOfVisible(
                    [&state](const core::Frame& frame, std::size_t) {
                        const auto rowMask = core::Session::faultRowMask(state, frame);
                        return core::computeVisibility(frame, state.boxes, state.thresholds,
                                                       rowMask.get())
                            .mask;
                    },
                    options);
                const auto remembered = [&](const core::Frame& frame, std::size_t f) {
                    {
                        std::lock_guard lock(memo->mutex);
                        if (auto it = memo->frames.find(f); it != memo->frames.end())
                            return it->second;
                    }
                    auto set = search(frame, f);
                    std::lock_guard lock(memo->mutex);
                    const std::size_t bytes = CandidateMemo::sizeOf(*set);
                    if (memo->bytes + bytes <= CandidateMemo::kBudget &&
                        memo->frames.emplace(f, set).second)
                        memo->bytes += bytes;
                    return set;
                };
                core::FaultMetricsSeries growth = core::trackedMetricsSeries(
                    frames,
                    [ds, &control, frames](std::size_t k) {
                        control.setProgress(float(k) / float(std::max<std::size_t>(frames, 1)));
                        if (control.cancelled())
                            throw std::runtime_error("cancelled");
                        return ds->frame(k);
                    },
                    remembered, faults, {}, &tracks);
                Events events{key, {}, 0, std::move(growth), conditionsText(state)};
                for (const core::FaultEvent& e : core::faultEvents(tracks)) {
                    PlotMark m;
                    m.frame = e.frame;
                    std::string names;
                    for (std::size_t k : e.faults)
                        names += (names.empty() ? "" : ", ") + faults[k].name;
                    switch (e.kind) {
                    case core::FaultEventKind::Appeared:
                        m.letter = 'A', m.color = IM_COL32(70, 140, 70, 255);
                        m.text = "appeared: " + names;
                        break;
                    case core::FaultEventKind::Linked:
                        m.letter = 'L', m.color = IM_COL32(200, 80, 30, 255);
                        m.text = "linked: " + names;
                        break;
                    case core::FaultEventKind::Split:
                        m.letter = 'S', m.color = IM_COL32(120, 60, 190, 255);
                        m.text = "split: " + names;
                        break;
                    }
                    ++events.count;
                    // One mark per frame and kind: "appeared: F1, F2" rather than a row of As.
                    if (!events.marks.empty() && events.marks.back().frame == m.frame &&
                        events.marks.back().letter == m.letter)
                        events.marks.back().text += ", " + names;
                    else
                        events.marks.push_back(std::move(m));
                }
                auto shared = std::make_shared<Events>(std::move(events));
                return [this, shared] { m_events = std::move(*shared); };
            },
            [&wb](const std::string& why) {
                if (why != "cancelled")
                    wb.error("Cannot find links and splits: " + why);
            },
            wb.now());
    }

    // "F1  44.2 .. 47.9" per fault: the metric's range over the frames where it is defined.
    void drawRanges(PanelContext& wb, const std::vector<const core::Fault*>& shown) {
        for (std::size_t k = 0; k < shown.size(); ++k) {
            if (m_values[k].empty())
                continue;
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (double v : m_values[k])
                if (std::isfinite(v))
                    lo = std::min(lo, v), hi = std::max(hi, v);
            const ImVec4 c(shown[k]->color[0], shown[k]->color[1], shown[k]->color[2], 1.0f);
            const float sw = ImGui::GetTextLineHeight() * 0.8f;
            const ImVec2 p = ImGui::GetCursorScreenPos();
            ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + 0.1f * sw),
                                                      ImVec2(p.x + sw, p.y + 1.1f * sw),
                                                      ImGui::ColorConvertFloat4ToU32(c));
            ImGui::Dummy(ImVec2(sw, sw));
            ImGui::SameLine();
            // The name shortened to leave the numbers their room; the numbers wrap below it
            // when the panel is narrow.
            const std::size_t now = std::min(wb.displayFrame(), m_values[k].size() - 1);
            char numbers[160];
            if (lo > hi)
                std::snprintf(numbers, sizeof numbers, "undefined in every frame");
            else if (std::isfinite(m_values[k][now]))
                std::snprintf(numbers, sizeof numbers, "min %.5g   max %.5g   frame %zu: %.5g", lo,
                              hi, now, m_values[k][now]);
            else
                std::snprintf(numbers, sizeof numbers, "min %.5g   max %.5g   frame %zu: undefined",
                              lo, hi, now);
            const float avail = ImGui::GetContentRegionAvail().x;
            textElided(shown[k]->name,
                       std::max(avail * 0.4f, avail - ImGui::CalcTextSize(numbers).x -
                                                  ImGui::GetStyle().ItemSpacing.x));
            flowSameLine(ImGui::CalcTextSize(numbers).x);
            hint("%s", numbers);
        }
    }

    FaultMetricsCache m_cache;
    std::size_t m_metric = 1; // dip
    std::vector<std::vector<double>> m_values;
    std::optional<std::size_t> m_scrub;
};

} // namespace

void addFaultMetricsSection(PanelExtensions& extensions) {
    auto section = std::make_shared<FaultMetricsSection>();
    extensions.faultSections.push_back(
        {"Metrics over time", [section](PanelContext& wb) { section->draw(wb); }, true});
}

} // namespace faultline::ui
