// addMallocHugePagesTunable: what it adds to GLIBC_TUNABLES, and when it leaves it alone.
#include "core/util/malloc_huge_pages.hpp"
#include "tests/common/sanitizers.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

using namespace faultline::core;

namespace {

// The environment variables a test changes, put back as they were after it.
class Environment {
  public:
    Environment() {
        for (const char* name : {"GLIBC_TUNABLES", "FAULTLINE_HUGE_PAGES"})
            if (const char* v = std::getenv(name))
                m_saved.emplace_back(name, std::string(v));
            else
                m_saved.emplace_back(name, std::nullopt);
    }
    ~Environment() {
        for (const auto& [name, value] : m_saved)
            if (value)
                ::setenv(name, value->c_str(), 1);
            else
                ::unsetenv(name);
    }

  private:
    std::vector<std::pair<const char*, std::optional<std::string>>> m_saved;
};

std::string tunables() {
    const char* v = std::getenv("GLIBC_TUNABLES");
    return v ? v : "";
}

bool kernelAdvisesHugePages() {
    std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    return std::getline(mode, line) && line.find("[madvise]") != std::string::npos;
}

bool sanitizerBuild() {
    return faultline::test::kUnderAddressSanitizer || faultline::test::kUnderThreadSanitizer;
}

} // namespace

TEST(MallocHugePages, TurnedOffByTheEnvironment) {
    Environment keep;
    ::unsetenv("GLIBC_TUNABLES");
    ::setenv("FAULTLINE_HUGE_PAGES", "0", 1);
    EXPECT_FALSE(addMallocHugePagesTunable());
    EXPECT_EQ(tunables(), "");
}

TEST(MallocHugePages, AUsersOwnSettingIsKept) {
    Environment keep;
    ::unsetenv("FAULTLINE_HUGE_PAGES");
    ::setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
    EXPECT_FALSE(addMallocHugePagesTunable());
    EXPECT_EQ(tunables(), "glibc.malloc.hugetlb=0");
}

TEST(MallocHugePages, AddedAfterOtherTunablesOnce) {
    if (sanitizerBuild() || !kernelAdvisesHugePages())
        GTEST_SKIP() << "huge pages are not madvise's here (or a sanitizer build): nothing to add";
    Environment keep;
    ::unsetenv("FAULTLINE_HUGE_PAGES");
    ::setenv("GLIBC_TUNABLES", "glibc.malloc.arena_max=2", 1);
    EXPECT_TRUE(addMallocHugePagesTunable());
    EXPECT_EQ(tunables(), "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
    EXPECT_FALSE(addMallocHugePagesTunable()) << "set already: a restart must not loop";
    EXPECT_EQ(tunables(), "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
    ::unsetenv("GLIBC_TUNABLES");
    EXPECT_TRUE(addMallocHugePagesTunable());
    EXPECT_EQ(tunables(), "glibc.malloc.hugetlb=1");
}
