// SurfaceCache: fault surfaces kept by (frame, member ids, field parameters), so scrubbing time or
// toggling a fault never rebuilds what was built, and a new iso-value only re-meshes.
#pragma once

#include "core/faults/fault.hpp"
#include "core/surface/fault_surface.hpp"

#include <cstdint>
#include <functional>
#include <list>
#include <mutex>
#include <vector>

namespace faultline::core {

struct SurfaceKey {
    std::int64_t frame = 0;
    std::uint64_t members = 0; // hashMemberIds
    std::uint64_t params = 0;  // fieldParamsHash (everything but iso)
    bool operator==(const SurfaceKey&) const = default;
};

class SurfaceCache {
  public:
    explicit SurfaceCache(std::size_t budgetBytes = std::size_t{1} << 30);

    // The surface for key + params.iso: cached, or re-meshed from a cached field when only the
    // iso-value changed (within the field's range), or built from gather()'s spheres. Thread-safe;
    // the build runs outside the lock. Exceptions from buildSurface pass through, nothing cached.
    // keepOnly: the caller only wants the surface kept (a journal's surface.build before its
    // exports): a new mesh is moved into the cache, not copied, and the result holds no mesh.
    SurfaceResult get(const SurfaceKey& key, const SurfaceParams& params,
                      const std::function<SphereSet()>& gather, Interrupter* interrupter = nullptr,
                      bool keepOnly = false);

    // Cached result without any work, or an empty result (field == nullptr).
    SurfaceResult find(const SurfaceKey& key, float iso) const;

    struct Counters {
        std::size_t hits = 0, remeshes = 0, builds = 0, evictions = 0;
    };
    Counters counters() const;
    std::size_t memoryBytes() const;
    void clear();

  private:
    struct Entry {
        SurfaceKey key;
        std::shared_ptr<const SurfaceField> field;
        std::vector<std::pair<float, SurfaceMesh>> meshes; // most recent first, a few isos
        std::size_t bytes = 0;
    };
    std::list<Entry>::iterator lookup(const SurfaceKey& key); // moves it to the front
    void insertLocked(Entry entry);
    static std::size_t meshBytes(const SurfaceMesh& mesh);

    mutable std::mutex m_mutex;
    std::list<Entry> m_entries; // most recently used first
    std::size_t m_budget;
    std::size_t m_bytes = 0;
    Counters m_counters;
};

} // namespace faultline::core
