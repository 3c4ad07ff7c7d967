#include "ui/workbench/view_composer.hpp"

#include "core/session/color_range.hpp"
#include "core/session/view_colors.hpp"

#include "core/model/frame_difference.hpp"
#include "core/selection/visibility.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace faultline::ui {

using core::Json;

namespace {

// Prefetch channels of difference colouring's reference frames (one per view, after the views').
constexpr std::size_t kReferenceChannel = 64;

} // namespace

ViewComposer::ViewComposer(core::Session& session, FrameStore& frames, SurfaceStore& surfaces,
                           JobRunner& jobs)
    : m_session(session), m_frames(frames), m_surfaces(surfaces), m_jobs(jobs) {}

const ViewDisplay* ViewComposer::view(const std::string& name) const {
    for (const auto& v : m_views)
        if (v.name == name)
            return &v;
    return nullptr;
}

void ViewComposer::reset() {
    m_views.clear();
    m_allFramesRange.clear();
    for (auto& [key, exact] : m_exactRanges)
        if (exact->job)
            exact->job->cancel();
    m_exactRanges.clear();
    m_differences.clear();
}

std::optional<std::array<double, 2>> ViewComposer::exactAllFramesRange(const core::ViewState& v) {
    const auto ds = m_session.dataset();
    if (!ds || ds->frameCount() == 0)
        return std::nullopt;
    // What the range depends on: the data, the variable, the difference and the strain
    // variables derived from motion (a strain.add with other options changes their values).
    std::ostringstream key;
    key << ds.get() << '|' << v.colorVariable << '|' << int(v.difference.mode) << '|'
        << v.difference.reference.relative << '|' << v.difference.reference.value;
    for (const core::StrainSpec& s : m_session.state().strains)
        key << "|s" << s.relative << ',' << s.reference << ',' << s.cutoff << ',' << s.prefix;
    auto [it, inserted] = m_exactRanges.try_emplace(key.str());
    if (!inserted)
        return it->second->ready ? it->second->range : std::nullopt;
    if (m_exactRanges.size() > 16) { // a few colourings at most are shown at once
        for (auto e = m_exactRanges.begin(); e != m_exactRanges.end(); ++e)
            if (e != it) {
                if (e->second->job)
                    e->second->job->cancel();
                m_exactRanges.erase(e);
                break;
            }
    }
    auto exact = it->second = std::make_shared<ExactRange>();
    core::ViewState view = v;
    view.rangeMode = core::RangeMode::AllFrames;
    exact->job = m_jobs.start(
        "Colour range over all frames",
        [ds, view, exact](JobControl& control) -> std::function<void()> {
            // Frame by frame, so it can stop; the union of each frame's range is the range
            // over all frames (each already symmetric about zero for a change).
            std::optional<core::ValueRange> all;
            const std::size_t n = ds->frameCount();
            for (std::size_t k = 0; k < n; ++k) {
                if (control.cancelled())
                    return {};
                control.setProgress(float(k) / float(n));
                if (const auto r = core::colorRangeOverFrames(*ds, view, {k}))
                    all = all ? core::ValueRange{std::min(all->low, r->low),
                                                 std::max(all->high, r->high)}
                              : *r;
            }
            return [exact, all] {
                if (all)
                    exact->range = std::array<double, 2>{all->low, all->high};
                exact->ready = true;
            };
        },
        [exact](const std::string&) { exact->ready = true; }, 0.0);
    return std::nullopt;
}

void ViewComposer::update(const Inputs& in) {
    const core::SessionState& s = m_session.state();
    auto ds = m_session.dataset();

    // The selection as shown: the session's plus any live edit.
    // Live edits run through the session's own ops on a copy (Session::preview), so a preview
    // shows exactly what the command would do, and one the op refuses shows nothing.
    std::vector<Json> edits;
    for (const auto& [key, cmd] : in.previews)
        if (cmd.value("op", "") != "frame.set")
            edits.push_back(cmd);
    core::Session::Preview shown = m_session.preview(edits);
    std::vector<core::CuttingBox> boxes = std::move(shown.boxes);
    std::vector<core::VariableThreshold> thresholds = std::move(shown.thresholds);
    std::map<std::string, core::CameraState> cameras;
    for (const auto& v : shown.views)
        cameras[v.name] = v.camera;
    m_displayBoxes = boxes;
    m_displayThresholds = thresholds;

    const std::size_t base = in.base;
    std::vector<ViewDisplay> next;
    std::size_t channel = 0;
    for (const auto& v : s.views) {
        ViewDisplay d;
        if (const ViewDisplay* old = view(v.name))
            d = *old;
        d.name = v.name;
        if (ds) {
            const long long count = static_cast<long long>(ds->frameCount());
            const long long want =
                v.frame.relative ? static_cast<long long>(base) + v.frame.value : v.frame.value;
            d.wantedFrame = static_cast<std::size_t>(std::clamp(want, 0LL, count - 1));
            if (auto f = m_frames.request(d.wantedFrame, channel)) {
                if (f != d.frame) { // bounds once per frame shown, not per UI frame
                    d.bounds = modelBounds(*f);
                    d.framed = false;
                    const ModelBounds& b = d.bounds;
                    d.sceneRadius = 0.5 * std::sqrt(std::pow(b.hi[0] - b.lo[0], 2) +
                                                    std::pow(b.hi[1] - b.lo[1], 2) +
                                                    std::pow(b.hi[2] - b.lo[2], 2));
                }
                d.frame = f;
                d.shownFrame = d.wantedFrame;
            }
        } else {
            d.frame.reset();
        }
        d.visibility.reset();
        if (d.frame) {
            // From the session's cache, keyed by what visibility depends on: the session's own
            // ops and every view showing the same frame and selection share one result.
            const core::Session::Visible visible =
                m_session.visibilityOf(d.frame, boxes, thresholds);
            d.visibility = visible.result;
            d.visibilityKey = visible.key;
        }
        // Camera: the session's (with a drag's preview); fitted to the model while unset.
        resolveColors(v, d, channel, in.selection);
        d.camera = cameras[v.name];
        if (d.camera.distance <= 0 && d.frame) {
            if (!d.framed) { // once per frame, and only for a view being fitted
                d.framing = framedBounds(*d.frame);
                d.framed = true;
            }
            d.camera = in.fit(v, d, d.camera);
        }
        d.surfaces = m_surfaces.surfacesFor(s, d.shownFrame, d.frame, in.now, d.visibility);
        next.push_back(std::move(d));
        ++channel;
    }
    m_views = std::move(next);
    m_surfaces.endFrame();
}

// What a view's spheres are coloured by and over which range: categories (the candidates
// previewed, or "faults"), a difference since a reference frame (once that frame is here), or
// the variable's own column (the renderer reads it from the frame).
void ViewComposer::resolveColors(const core::ViewState& v, ViewDisplay& d, std::size_t channel,
                                 const UiSelection& selection) {
    d.colorColumn.reset();
    d.palette.clear();
    d.legend.clear();
    d.colorTitle = v.colorVariable;
    d.colorRange = {0, 1};
    d.colorHasNoValue = false;
    if (!d.frame)
        return;
    if (const CategoryColoring* cat = categoriesFor(v, d, selection)) {
        d.colorColumn = cat->values;
        d.palette = cat->palette;
        d.legend = legendEntries(*cat);
        d.colorTitle = d.colorColumn->name;
        d.colorRange = {0.0, static_cast<double>(d.palette.size())};
        return;
    }
    // The rule is core's (core::colorView), shared with figures and movies; what is slow comes
    // from this composer's caches and background jobs.
    core::ViewColorSources sources;
    sources.frame = [&](std::size_t ref) {
        return m_frames.request(ref, kReferenceChannel + channel);
    };
    sources.difference = [&](const std::shared_ptr<const core::Frame>& now,
                             const std::shared_ptr<const core::Frame>& ref,
                             core::ColorDifference::Mode mode, const std::string& variable) {
        return mode == core::ColorDifference::Mode::Change
                   ? m_differences.change(now, ref, variable)
                   : m_differences.displacement(now, ref);
    };
    // The range over the frames seen so far, until the range over every frame is worked out
    // (in the background): the view then takes it, as figures and movies do.
    sources.allFrames = [&](const core::ViewState& view, const std::string& title,
                            core::ValueRange inFrame) {
        auto& all = m_allFramesRange.try_emplace(title, std::array{inFrame.low, inFrame.high})
                        .first->second;
        all = {std::min(all[0], inFrame.low), std::max(all[1], inFrame.high)};
        const auto exact = exactAllFramesRange(view);
        return exact ? core::ValueRange{(*exact)[0], (*exact)[1]}
                     : core::ValueRange{all[0], all[1]};
    };
    // Kept per visibility (a new frame or threshold brings a new one): the percentiles cost a
    // selection over the spheres shown, once rather than at every redraw.
    sources.visibleRange = [&](const core::Frame& frame, const core::VisibilityResult&,
                               const std::string& variable,
                               bool percentiles) -> std::optional<core::ValueRange> {
        auto hit = std::find_if(m_visibleRanges.begin(), m_visibleRanges.end(), [&](const auto& e) {
            return e.visibility == d.visibility && e.variable == variable &&
                   e.percentiles == percentiles;
        });
        if (hit == m_visibleRanges.end()) {
            if (m_visibleRanges.size() >= 8)
                m_visibleRanges.erase(m_visibleRanges.begin());
            m_visibleRanges.push_back(
                {d.visibility, variable, percentiles,
                 percentiles
                     ? core::maskedQuantiles(frame, variable, d.visibility->mask, 0.01, 0.99)
                     : core::maskedRange(frame, variable, d.visibility->mask)});
            hit = m_visibleRanges.end() - 1;
        }
        if (!hit->range)
            return std::nullopt;
        return core::ValueRange{hit->range->first, hit->range->second};
    };
    const core::ViewColoring c = core::colorView(v, d.shownFrame, m_session.dataset()->frameCount(),
                                                 d.frame, d.visibility.get(), sources);
    d.colorColumn = c.column;
    d.colorTitle = c.title;
    d.colorRange = {c.range.low, c.range.high};
    d.colorHasNoValue = !c.column && !v.colorVariable.empty() &&
                        v.difference.mode == core::ColorDifference::Mode::None &&
                        hasNoValue(d.frame, v.colorVariable);
}

// Whether `frame` holds `variable` as a column without one finite value. Such a column's
// cached range is [0, 0] (cacheColumnRange, strainFromMotion), so only those are scanned, once
// per frame (the answer kept, the frame not held).
bool ViewComposer::hasNoValue(const std::shared_ptr<const core::Frame>& frame,
                              const std::string& variable) {
    const core::AttributeColumn* c = frame->attribute(variable);
    if (!c || !c->mayHaveNoValue())
        return false;
    // The same frame object (an expired entry keeps its control block, so no new frame matches).
    for (const auto& e : m_noValue)
        if (!e.frame.owner_before(frame) && !frame.owner_before(e.frame) && e.variable == variable)
            return e.none;
    const bool none = c->hasNoValue();
    if (m_noValue.size() >= 8)
        m_noValue.erase(m_noValue.begin());
    m_noValue.push_back({frame, variable, none});
    return none;
}

const CategoryColoring* ViewComposer::categoriesFor(const core::ViewState& v, const ViewDisplay& d,
                                                    const UiSelection& selection) {
    if (!d.frame)
        return nullptr;
    if (selection.candidates && v.name == "main" && selection.candidates->frame == d.frame)
        return &selection.candidates->coloring;
    if (v.colorVariable != kFaultsVariable || d.frame->attribute(kFaultsVariable))
        return nullptr;
    if (m_faultsKeyVersion != m_session.version()) { // hashing every member id: once per change
        m_faultsKeyVersion = m_session.version();
        m_faultsKey = faultColoringKey(m_session.state().faults);
    }
    const std::uint64_t key = m_faultsKey;
    for (auto& e : m_faultColorings)
        if (e.frame == d.frame && e.key == key)
            return &e.coloring;
    if (m_faultColorings.size() >= 4)
        m_faultColorings.erase(m_faultColorings.begin());
    m_faultColorings.push_back({d.frame, key, faultColoring(*d.frame, m_session.state().faults)});
    return &m_faultColorings.back().coloring;
}

} // namespace faultline::ui
