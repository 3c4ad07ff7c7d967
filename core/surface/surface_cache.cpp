#include "core/surface/surface_cache.hpp"

namespace faultline::core {

namespace {
constexpr std::size_t kMeshesPerEntry = 4;
}

SurfaceCache::SurfaceCache(std::size_t budgetBytes) : m_budget(budgetBytes) {}

std::size_t SurfaceCache::meshBytes(const SurfaceMesh& mesh) {
    return mesh.positions.size() * 3 * sizeof(std::array<float, 3>) +
           mesh.indices.size() * sizeof(std::uint32_t);
}

std::list<SurfaceCache::Entry>::iterator SurfaceCache::lookup(const SurfaceKey& key) {
    for (auto it = m_entries.begin(); it != m_entries.end(); ++it)
        if (it->key == key) {
            m_entries.splice(m_entries.begin(), m_entries, it);
            return m_entries.begin();
        }
    return m_entries.end();
}

SurfaceResult SurfaceCache::find(const SurfaceKey& key, float iso) const {
    std::lock_guard lock(m_mutex);
    for (const auto& e : m_entries)
        if (e.key == key)
            for (const auto& [meshIso, mesh] : e.meshes)
                if (meshIso == iso)
                    return {e.field, mesh, iso};
    return {};
}

SurfaceResult SurfaceCache::get(const SurfaceKey& key, const SurfaceParams& params,
                                const std::function<SphereSet()>& gather, Interrupter* interrupter,
                                bool keepOnly) {
    std::shared_ptr<const SurfaceField> field;
    {
        std::lock_guard lock(m_mutex);
        auto it = lookup(key);
        if (it != m_entries.end()) {
            for (const auto& [iso, mesh] : it->meshes)
                if (iso == params.iso) {
                    ++m_counters.hits;
                    return keepOnly ? SurfaceResult{it->field, {}, iso}
                                    : SurfaceResult{it->field, mesh, iso};
                }
            if (it->field->supportsIso(params.iso))
                field = it->field;
        }
    }
    if (field) {
        SurfaceMesh mesh = remesh(*field, params.iso, interrupter);
        std::lock_guard lock(m_mutex);
        ++m_counters.remeshes;
        auto it = lookup(key);
        if (it != m_entries.end() && it->field == field) {
            const std::size_t bytes = meshBytes(mesh);
            // Moved in when the caller reads no mesh, else copied.
            it->meshes.insert(it->meshes.begin(),
                              {params.iso, keepOnly ? std::move(mesh) : SurfaceMesh(mesh)});
            m_bytes += bytes;
            it->bytes += bytes;
            while (it->meshes.size() > kMeshesPerEntry) {
                m_bytes -= meshBytes(it->meshes.back().second);
                it->bytes -= meshBytes(it->meshes.back().second);
                it->meshes.pop_back();
            }
        }
        if (keepOnly)
            return {field, {}, params.iso};
        return {field, std::move(mesh), params.iso};
    }
    SurfaceResult built = buildSurface(gather(), params, interrupter);
    std::lock_guard lock(m_mutex);
    ++m_counters.builds;
    Entry entry;
    entry.key = key;
    entry.field = built.field;
    entry.bytes = built.field->memoryBytes() + meshBytes(built.mesh);
    entry.meshes.emplace_back(built.iso,
                              keepOnly ? std::move(built.mesh) : SurfaceMesh(built.mesh));
    insertLocked(std::move(entry));
    return keepOnly ? SurfaceResult{built.field, {}, built.iso} : built;
}

void SurfaceCache::insertLocked(Entry entry) {
    auto old = lookup(entry.key);
    if (old != m_entries.end()) {
        m_bytes -= old->bytes;
        m_entries.erase(old);
    }
    m_bytes += entry.bytes;
    m_entries.push_front(std::move(entry));
    // Keep the newest entry even when it alone exceeds the budget.
    while (m_bytes > m_budget && m_entries.size() > 1) {
        m_bytes -= m_entries.back().bytes;
        m_entries.pop_back();
        ++m_counters.evictions;
    }
}

SurfaceCache::Counters SurfaceCache::counters() const {
    std::lock_guard lock(m_mutex);
    return m_counters;
}

std::size_t SurfaceCache::memoryBytes() const {
    std::lock_guard lock(m_mutex);
    return m_bytes;
}

void SurfaceCache::clear() {
    std::lock_guard lock(m_mutex);
    m_entries.clear();
    m_bytes = 0;
}

} // namespace faultline::core
