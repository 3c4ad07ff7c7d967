// FAULTLINE_TBB_THREADS (tests/common/test_main.cpp): the ThreadSanitizer run asks for 8 TBB
// threads on any machine; check that the tests' loops do get an arena of that size.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <cstdlib>

TEST(TestMain, TbbLoopsRunInAnArenaOfTheThreadsAsked) {
    const char* n = std::getenv("FAULTLINE_TBB_THREADS");
    if (!n || std::atoi(n) <= 0)
        GTEST_SKIP() << "FAULTLINE_TBB_THREADS is not set";
    const int threads = std::atoi(n);
    EXPECT_EQ(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism),
              std::size_t(threads));
    if (threads > tbb::info::default_concurrency()) { // more than the machine's cores
        EXPECT_EQ(tbb::this_task_arena::max_concurrency(), threads);
    }
}
