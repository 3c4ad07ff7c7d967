#include "core/util/scratch_array.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <deque>
#include <mutex>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace faultline::core {

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

// Whole huge pages (the last one is resident whole once touched).
std::size_t pooledSize(std::size_t bytes) { return (bytes + kHugePage - 1) & ~(kHugePage - 1); }

struct Block {
    void* p;
    std::size_t bytes; // pooledSize of the request
};

struct Pool {
    std::mutex mutex;
    std::deque<Block> kept; // oldest freed first
    std::size_t bytes = 0;

    ~Pool() {
        for (const Block& b : kept)
            std::free(b.p);
    }
};

Pool& pool() {
    static Pool p;
    return p;
}

} // namespace

void* detail::acquireScratch(std::size_t bytes, std::size_t alignment) {
    if (bytes < kHugePage) {
        // aligned_alloc wants a size that is a multiple of the alignment.
        const std::size_t align = std::max(alignment, alignof(std::max_align_t));
        void* p = std::aligned_alloc(align, std::max(align, (bytes + align - 1) & ~(align - 1)));
        if (!p)
            throw std::bad_alloc();
        return p;
    }
    const std::size_t size = pooledSize(bytes);
    {
        Pool& kept = pool();
        const std::lock_guard lock(kept.mutex);
        // The most recently freed block of this size: the one most likely still in a cache.
        for (auto it = kept.kept.rbegin(); it != kept.kept.rend(); ++it)
            if (it->bytes == size) {
                void* p = it->p;
                kept.bytes -= size;
                kept.kept.erase(std::next(it).base());
                return p;
            }
    }
    void* p = std::aligned_alloc(kHugePage, size);
    if (!p)
        throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, size, MADV_HUGEPAGE); // a hint: refused, the pages are plain
#endif
    return p;
}

void detail::releaseScratch(void* p, std::size_t bytes) noexcept {
    if (!p)
        return;
    const std::size_t size = pooledSize(bytes);
    if (bytes < kHugePage || size > kScratchPoolBytes) {
        std::free(p);
        return;
    }
    Pool& kept = pool();
    const std::lock_guard lock(kept.mutex);
    while (kept.bytes + size > kScratchPoolBytes) {
        std::free(kept.kept.front().p);
        kept.bytes -= kept.kept.front().bytes;
        kept.kept.pop_front();
    }
    // A deque's push_back may throw; the block then goes back to the system.
    try {
        kept.kept.push_back({p, size});
        kept.bytes += size;
    } catch (...) {
        std::free(p);
    }
}

std::size_t scratchPoolBytes() {
    Pool& kept = pool();
    const std::lock_guard lock(kept.mutex);
    return kept.bytes;
}

void releaseScratchPool() {
    Pool& kept = pool();
    const std::lock_guard lock(kept.mutex);
    for (const Block& b : kept.kept)
        std::free(b.p);
    kept.kept.clear();
    kept.bytes = 0;
}

} // namespace faultline::core
