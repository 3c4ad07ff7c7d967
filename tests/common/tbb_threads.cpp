// FAULTLINE_TBB_THREADS=N caps TBB's threads for the whole test run (tbb::global_control).
// scripts/hardening.sh runs the ThreadSanitizer build with N=1: Debian's libtbb is not built
// with TSan, so its work-stealing hand-offs look like races on every parallel loop; with TBB
// inline, TSan checks what is ours (background jobs, the prefetcher, caches, Python's worker).
#include <tbb/global_control.h>

#include <cstdlib>
#include <memory>

namespace {

struct TbbThreads {
    std::unique_ptr<tbb::global_control> control;
    TbbThreads() {
        if (const char* n = std::getenv("FAULTLINE_TBB_THREADS"); n && std::atoi(n) > 0)
            control = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, std::size_t(std::atoi(n)));
    }
};
const TbbThreads kTbbThreads;

} // namespace
