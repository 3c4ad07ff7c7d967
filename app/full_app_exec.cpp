// `faultline` hands the heavy commands to faultline-app, found beside its own executable.
#include "app/cli.hpp"
#include "core/util/malloc_huge_pages.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace faultline::app {

int runFullApp(int argc, char** argv) {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path app =
        (ec ? std::filesystem::path(argv[0]).parent_path() : self.parent_path()) / "faultline-app";
    std::vector<char*> args(argv, argv + argc);
    args.push_back(nullptr);
    const std::string path = app.string();
    core::addMallocHugePagesTunable(); // read at the app's start: no restart there
    execv(path.c_str(), args.data());
    std::fprintf(stderr,
                 "faultline: cannot start %s (%s); it holds the workbench, replay and render and "
                 "is built beside faultline\n",
                 path.c_str(), std::strerror(errno));
    return 127;
}

} // namespace faultline::app
