// SurfaceStore: the workbench's fault surfaces. Each view asks for the meshes of the visible
// surfaces in the frame it shows; a mesh not built yet is built in a background job (progress,
// cancel) through a core::SurfaceCache, so scrubbing back or toggling a fault never rebuilds,
// an iso-only change re-meshes, and a job nobody asks for any more is cancelled.
#pragma once

#include "core/model/frame.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/session_state.hpp"
#include "core/surface/surface_cache.hpp"
#include "ui/context/jobs.hpp"
#include "ui/render/renderer.hpp"
#include "ui/viewport/view_renderer.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace faultline::ui {

struct SurfaceStatus {
    // NotFormed: none of the fault's spheres passes the thresholds in this frame (no surface).
    enum class State { None, Waiting, Building, Ready, Failed, NotFormed };
    State state = State::None;
    float progress = -1.0f; // Building: 0..1, < 0 unknown
    std::string error;      // Failed
    std::size_t spheres = 0, triangles = 0;
    double seconds = 0.0; // how long the build took
    // Ready with no triangles: the largest value the field's grid holds (the iso lies above it
    // when it is below the iso), to say why the surface is empty.
    float fieldMax = 0.0f;
    float iso = 0.0f;
    // Ready: the iso-values worth a slider for this fault and kernel, [low, high]: `high` where
    // the surface has shrunk into the spheres, `low` a loose hull (core::isoSliderRange).
    float isoLow = 0.0f, isoHigh = 0.0f;
};

class SurfaceStore {
  public:
    explicit SurfaceStore(JobRunner& jobs);
    SurfaceStore(const SurfaceStore&) = delete;
    SurfaceStore& operator=(const SurfaceStore&) = delete;

    // The ready surfaces for a view showing `frame` (dataset index frameIndex), one per visible
    // surface setting whose fault exists; starts (one at a time) the builds still missing.
    // `visibility` (the view's) gives the visible spheres' surface (core::kVisibleSpheres).
    std::vector<ViewSurface>
    surfacesFor(const core::SessionState& state, std::size_t frameIndex,
                const std::shared_ptr<const core::Frame>& frame, double now,
                const std::shared_ptr<const core::VisibilityResult>& visibility = nullptr);
    // The state of a fault's surface in a frame, as last asked for by surfacesFor (with the
    // view's frame and visibility for the visible spheres' surface).
    SurfaceStatus
    status(const core::SessionState& state, const std::string& fault, std::size_t frameIndex,
           const std::shared_ptr<const core::Frame>& frame = nullptr,
           const std::shared_ptr<const core::VisibilityResult>& visibility = nullptr) const;
    // What a surface setting is built from in a view showing `frame`: the fault as formed there
    // (core::faultAsFormed: its members passing the thresholds; none before it formed), or the
    // visible spheres (kept while the frame and visibility stay the same). Null when there is none;
    // valid until the next call (copy it to keep it).
    const core::Fault*
    sourceOf(const core::SessionState& state, const std::string& name,
             const std::shared_ptr<const core::Frame>& frame,
             const std::shared_ptr<const core::VisibilityResult>& visibility) const;
    // Once per UI frame, after every view asked: cancels builds nobody asked for this frame.
    void endFrame();
    // Forgets every mesh (new data).
    void clear();

    std::size_t buildsStarted() const { return m_buildsStarted; }
    // What was built, for exports of the surfaces shown (shared with their jobs).
    const std::shared_ptr<core::SurfaceCache>& cache() const { return m_cache; }

  private:
    using Key = std::tuple<std::int64_t, std::uint64_t, std::uint64_t,
                           float>; // frame, members, params, iso
    struct Entry {
        std::shared_ptr<Job> job;
        std::shared_ptr<const MeshData> mesh;
        SurfaceStatus status;
        std::uint64_t lastUse = 0;
    };
    std::optional<Key> keyOf(const core::SurfaceSettings& settings, const core::Fault& fault,
                             std::size_t frameIndex, const core::Frame* frame) const;
    void startBuild(const Key& key, Entry& entry, const core::SurfaceSettings& settings,
                    const core::Fault& fault, std::shared_ptr<const core::Frame> frame, double now);
    void prune();

    JobRunner& m_jobs;
    std::shared_ptr<core::SurfaceCache> m_cache; // shared with running jobs
    std::map<Key, Entry> m_entries;
    struct VisibleSource {
        std::shared_ptr<const core::Frame> frame;
        std::shared_ptr<const core::VisibilityResult> visibility;
        core::Fault fault;
    };
    mutable std::vector<VisibleSource> m_visibleSources; // most recent last, a few views' worth
    struct FormedSource { // a fault as formed in a frame (core::faultAsFormed)
        std::shared_ptr<const core::Frame> frame;
        std::vector<core::VariableThreshold> thresholds;
        core::Fault source, formed;
    };
    mutable std::vector<FormedSource> m_formedSources; // most recent last
    std::uint64_t m_tick = 1;
    std::size_t m_buildsStarted = 0;
};

} // namespace faultline::ui
