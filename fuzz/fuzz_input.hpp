// Shared by the fuzz targets: bytes as a file path (memfd: no disk I/O) and the rule every
// target checks — bad input may only ever raise InputError (or CommandError), nothing else.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace faultline::fuzz {

class MemoryFile {
  public:
    MemoryFile(const std::uint8_t* data, std::size_t size) {
        m_fd = ::memfd_create("faultline-fuzz", 0);
        std::size_t done = 0;
        while (m_fd >= 0 && done < size) {
            const ssize_t n = ::write(m_fd, data + done, size - done);
            if (n <= 0)
                break;
            done += static_cast<std::size_t>(n);
        }
        m_path = "/proc/self/fd/" + std::to_string(m_fd);
    }
    ~MemoryFile() {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    const std::string& path() const { return m_path; }

  private:
    int m_fd = -1;
    std::string m_path;
};

} // namespace faultline::fuzz
