// The tests' main. FAULTLINE_TBB_THREADS=N sets how many threads TBB's parallel loops use for
// the whole run: N = 1 runs them inline; N above the machine's cores runs every test inside an
// arena of N slots (tbb::task_arena), so a 2-core machine still runs loops on N threads (issue 42:
// scripts/hardening.sh runs the ThreadSanitizer build with N = 8 against a TBB built with TSan).
// Loops that background threads start run in those threads' own default arenas.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <memory>

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
    const char* n = std::getenv("FAULTLINE_TBB_THREADS");
    const int threads = n ? std::atoi(n) : 0;
    if (threads <= 0)
        return RUN_ALL_TESTS();
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    if (threads <= tbb::info::default_concurrency())
        return RUN_ALL_TESTS();
    tbb::task_arena arena(threads);
    return arena.execute([] { return RUN_ALL_TESTS(); });
}
