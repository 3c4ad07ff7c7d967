#include "core/util/malloc_huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define FAULTLINE_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define FAULTLINE_SANITIZED 1
#endif

namespace faultline::core {

bool addMallocHugePagesTunable() {
#if defined(FAULTLINE_SANITIZED) || !defined(__GLIBC__)
    return false; // the sanitizers bring their own allocator; other C libraries other knobs
#else
    if (const char* v = std::getenv("FAULTLINE_HUGE_PAGES");
        v != nullptr && std::strcmp(v, "0") == 0)
        return false;
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    std::string value = tunables != nullptr ? tunables : "";
    if (value.find("glibc.malloc.hugetlb") != std::string::npos)
        return false; // set, by us (after the restart) or by the user
    std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    if (!std::getline(mode, line) || line.find("[madvise]") == std::string::npos)
        return false;
    value += value.empty() ? "glibc.malloc.hugetlb=1" : ":glibc.malloc.hugetlb=1";
    return ::setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0;
#endif
}

void restartWithMallocHugePages(char** argv) {
    if (argv == nullptr || argv[0] == nullptr || !addMallocHugePagesTunable())
        return;
    ::execv("/proc/self/exe", argv);
    // Could not: run on without (the tunable stays for children, which is harmless).
}

} // namespace faultline::core
