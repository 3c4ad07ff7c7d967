// Scratch arrays of megabytes, left uninitialised, kept for reuse once freed and backed by
// transparent huge pages where the kernel offers them on request (Linux, THP "madvise" or
// "always"). Fresh memory costs its first touch: a page fault per 4 kB page, or the zeroing of
// each 2 MB page; for strain from motion on 525k spheres (about 50 MB of scratch a frame) that
// was a sixth of its time, paid again for every frame of a scrub. A freed block waits in a pool
// (at most kScratchPoolBytes, the oldest freed first) for the next request of the same size.
// Arrays under 2 MB are plain malloc.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>

namespace faultline::core {

inline constexpr std::size_t kScratchPoolBytes = std::size_t(256) << 20;

namespace detail {
// Aligned to `alignment` (a power of two, at most 2 MB). Throws std::bad_alloc.
void* acquireScratch(std::size_t bytes, std::size_t alignment);
void releaseScratch(void* p, std::size_t bytes) noexcept;
} // namespace detail

struct ScratchDeleter {
    std::size_t bytes = 0;
    void operator()(void* p) const noexcept { detail::releaseScratch(p, bytes); }
};

template <typename T> using ScratchArray = std::unique_ptr<T[], ScratchDeleter>;

// `count` elements, not initialised, aligned as T asks. Throws std::bad_alloc.
template <typename T> ScratchArray<T> makeScratchArray(std::size_t count) {
    static_assert(std::is_trivially_default_constructible_v<T> &&
                  std::is_trivially_destructible_v<T>);
    if (count > (std::size_t(1) << 60) / sizeof(T))
        throw std::bad_alloc();
    const std::size_t bytes = count * sizeof(T);
    return ScratchArray<T>(static_cast<T*>(detail::acquireScratch(bytes, alignof(T))),
                           ScratchDeleter{bytes});
}

// The bytes the pool keeps now, and giving them back to the system (tests; a caller that
// wants the memory back at once).
std::size_t scratchPoolBytes();
void releaseScratchPool();

} // namespace faultline::core
