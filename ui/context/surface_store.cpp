#include "ui/context/surface_store.hpp"

#include "core/session/fault_surface_request.hpp"
#include "core/surface/fault_surface.hpp"
#include "ui/context/job_interrupter.hpp"
#include "ui/render/surface_mesh.hpp"

#include <algorithm>
#include <chrono>

namespace faultline::ui {

namespace {

constexpr std::size_t kKeepEntries = 48;

} // namespace

SurfaceStore::SurfaceStore(JobRunner& jobs)
    : m_jobs(jobs), m_cache(std::make_shared<core::SurfaceCache>()) {}

std::optional<SurfaceStore::Key> SurfaceStore::keyOf(const core::SurfaceSettings& settings,
                                                     const core::Fault& fault,
                                                     std::size_t frameIndex,
                                                     const core::Frame* frame) const {
    const core::SurfaceParams params = core::surfaceParamsOf(settings, fault);
    const core::SurfaceKey k = core::surfaceKeyOf(frameIndex, frame, fault, settings, params);
    return Key{k.frame, k.members, k.params, params.iso};
}

const core::Fault*
SurfaceStore::sourceOf(const core::SessionState& state, const std::string& name,
                       const std::shared_ptr<const core::Frame>& frame,
                       const std::shared_ptr<const core::VisibilityResult>& visibility) const {
    if (!core::isVisibleSpheres(name)) {
        const core::Fault* fault = state.fault(name);
        if (!fault || !frame ||
            std::none_of(state.thresholds.begin(), state.thresholds.end(),
                         [](const core::VariableThreshold& t) { return t.enabled; }))
            return fault;
        for (auto& f : m_formedSources)
            if (f.frame == frame && f.thresholds == state.thresholds && f.source == *fault)
                return &f.formed;
        if (m_formedSources.size() >= 16)
            m_formedSources.erase(m_formedSources.begin());
        m_formedSources.push_back({frame, state.thresholds, *fault,
                                   core::faultAsFormed(*frame, *fault, state.thresholds)});
        return &m_formedSources.back().formed;
    }
    if (!frame || !visibility)
        return nullptr;
    for (auto& v : m_visibleSources)
        if (v.frame == frame && v.visibility == visibility)
            return &v.fault;
    if (m_visibleSources.size() >= 4)
        m_visibleSources.erase(m_visibleSources.begin());
    m_visibleSources.push_back({frame, visibility, core::visibleSpheresFault(*frame, *visibility)});
    // (A few views' worth; an export's own visibility passes through.)
    return &m_visibleSources.back().fault;
}

std::vector<ViewSurface>
SurfaceStore::surfacesFor(const core::SessionState& state, std::size_t frameIndex,
                          const std::shared_ptr<const core::Frame>& frame, double now,
                          const std::shared_ptr<const core::VisibilityResult>& visibility) {
    std::vector<ViewSurface> out;
    if (!frame)
        return out;
    for (const auto& settings : state.surfaces) {
        if (!settings.visible)
            continue;
        const core::Fault* fault = sourceOf(state, settings.fault, frame, visibility);
        if (!fault || !fault->visible || fault->ids.empty()) // none formed in this frame yet
            continue;
        const auto key = keyOf(settings, *fault, frameIndex, frame.get());
        if (!key)
            continue;
        Entry& e = m_entries[*key];
        e.lastUse = m_tick;
        if (e.mesh) {
            out.push_back({settings.fault, e.mesh, static_cast<float>(settings.opacity)});
            continue;
        }
        if (e.job || e.status.state == SurfaceStatus::State::Failed)
            continue;
        const bool busy = std::any_of(m_entries.begin(), m_entries.end(),
                                      [](const auto& kv) { return kv.second.job != nullptr; });
        if (busy) {
            e.status.state = SurfaceStatus::State::Waiting;
            continue;
        }
        startBuild(*key, e, settings, *fault, frame, now);
    }
    return out;
}

void SurfaceStore::startBuild(const Key& key, Entry& entry, const core::SurfaceSettings& settings,
                              const core::Fault& fault, std::shared_ptr<const core::Frame> frame,
                              double now) {
    ++m_buildsStarted;
    entry.status = {};
    entry.status.state = SurfaceStatus::State::Building;
    auto work = [cache = m_cache, frame = std::move(frame),
                 request = core::FaultSurfaceRequest{fault, settings},
                 frameIndex = static_cast<std::size_t>(std::get<0>(key)), this,
                 key](JobControl& control) {
        const auto t0 = std::chrono::steady_clock::now();
        JobInterrupter interrupter(control);
        const core::SurfaceResult result =
            core::buildFaultSurface(*frame, request, &interrupter, {cache.get(), frameIndex});
        auto mesh = std::make_shared<const MeshData>(toMeshData(result.mesh));
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::size_t count = result.field ? result.field->sphereCount() : 0;
        float fieldMax = 0.0f;
        if (mesh->indices.empty() && result.field) {
            // The grid's largest value; with no grid at all (the plan found the field below the
            // iso everywhere) the largest at the sphere centres.
            fieldMax = result.field->storedRange()[1];
            if (!(fieldMax > 0.0f))
                fieldMax = result.field->maxAtCentres();
        }
        const float iso = result.iso;
        const std::array<float, 2> slider =
            result.field ? result.field->isoSliderRange() : std::array<float, 2>{0.0f, 0.0f};
        return std::function<void()>([this, key, mesh, seconds, count, fieldMax, iso, slider] {
            auto it = m_entries.find(key);
            if (it == m_entries.end())
                return;
            Entry& e = it->second;
            e.job.reset();
            e.mesh = mesh;
            e.status.state = SurfaceStatus::State::Ready;
            e.status.progress = 1.0f;
            e.status.spheres = count;
            e.status.triangles = mesh->indices.size() / 3;
            e.status.seconds = seconds;
            e.status.fieldMax = fieldMax;
            e.status.iso = iso;
            e.status.isoLow = slider[0];
            e.status.isoHigh = slider[1];
        });
    };
    auto fail = [this, key](const std::string& error) {
        auto it = m_entries.find(key);
        if (it == m_entries.end())
            return;
        it->second.job.reset();
        it->second.status.state = SurfaceStatus::State::Failed;
        it->second.status.error = error;
    };
    entry.job = m_jobs.start("Surface of " + fault.name, std::move(work), std::move(fail), now);
}

SurfaceStatus
SurfaceStore::status(const core::SessionState& state, const std::string& fault,
                     std::size_t frameIndex, const std::shared_ptr<const core::Frame>& frame,
                     const std::shared_ptr<const core::VisibilityResult>& visibility) const {
    const core::SurfaceSettings* settings = state.surface(fault);
    if (!settings)
        return {};
    const core::Fault* source = sourceOf(state, fault, frame, visibility);
    if (!source)
        return {};
    if (source->ids.empty() && !core::isVisibleSpheres(fault) && frame) {
        SurfaceStatus s;
        s.state = SurfaceStatus::State::NotFormed;
        return s;
    }
    const auto key = keyOf(*settings, *source, frameIndex, frame.get());
    if (!key)
        return {};
    auto it = m_entries.find(*key);
    if (it == m_entries.end())
        return {};
    SurfaceStatus s = it->second.status;
    if (it->second.job)
        s.progress = it->second.job->progress();
    return s;
}

void SurfaceStore::endFrame() {
    for (auto& [key, e] : m_entries)
        if (e.job && e.lastUse != m_tick && !e.job->cancelRequested()) {
            e.job->cancel(); // its result is dropped; the entry may be asked for again later
            e.job.reset();
            e.status = {};
        }
    for (auto& [key, e] : m_entries)
        if (!e.job && !e.mesh && e.status.state == SurfaceStatus::State::Waiting &&
            e.lastUse != m_tick)
            e.status = {};
    prune();
    ++m_tick;
}

void SurfaceStore::prune() {
    if (m_entries.size() <= kKeepEntries)
        return;
    std::vector<std::pair<std::uint64_t, Key>> idle;
    for (const auto& [key, e] : m_entries)
        if (!e.job && e.lastUse != m_tick)
            idle.push_back({e.lastUse, key});
    std::sort(idle.begin(), idle.end());
    for (std::size_t k = 0; k + kKeepEntries < m_entries.size() && k < idle.size(); ++k)
        m_entries.erase(idle[k].second);
}

void SurfaceStore::clear() {
    for (auto& [key, e] : m_entries)
        if (e.job)
            e.job->cancel();
    m_entries.clear();
    m_visibleSources.clear(); // they hold frames of the data being closed
    m_formedSources.clear();
    m_cache->clear();
}

} // namespace faultline::ui
