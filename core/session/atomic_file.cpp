#include "core/session/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace faultline::core {

void writeFileAtomically(const std::string& path, std::string_view content) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(folder, ec);
    std::string tmp = (folder / ("." + target.filename().string() + ".tmpXXXXXX")).string();
    const int fd = ::mkstemp(tmp.data());
    auto fail = [&](const std::string& what) {
        const std::string reason = std::strerror(errno);
        if (fd >= 0)
            ::close(fd);
        ::unlink(tmp.c_str());
        throw std::runtime_error(path + ": cannot " + what + ": " + reason);
    };
    if (fd < 0)
        throw std::runtime_error(path + ": cannot create a file in " + folder.string() + ": " +
                                 std::strerror(errno));
    std::size_t done = 0;
    while (done < content.size()) {
        const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            fail("write");
        }
        done += static_cast<std::size_t>(n);
    }
    ::fchmod(fd, 0644);
    if (::fsync(fd) != 0)
        fail("flush to disk");
    if (::close(fd) != 0) {
        ::unlink(tmp.c_str());
        throw std::runtime_error(path + ": cannot close: " + std::strerror(errno));
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        ::unlink(tmp.c_str());
        throw std::runtime_error(path + ": cannot replace: " + reason);
    }
    const int dirFd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (dirFd >= 0) {
        ::fsync(dirFd);
        ::close(dirFd);
    }
}

} // namespace faultline::core
