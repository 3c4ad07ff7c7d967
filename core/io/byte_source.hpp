// ByteSource: sequential or ranged reads of a file, gzip-compressed or not (zlib decides).
// Reads are bounded: nothing allocates more than the file can justify.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace faultline::core {

class GzipReader;

class ByteSource {
  public:
    explicit ByteSource(const std::string& path); // throws InputError when it cannot open
    ~ByteSource();
    ByteSource(const ByteSource&) = delete;
    ByteSource& operator=(const ByteSource&) = delete;

    // Reads up to n bytes; returns 0 at the end. Throws InputError on a corrupt gzip stream.
    std::size_t read(char* dst, std::size_t n);
    // Positions at an offset in the uncompressed stream (gzip: it inflates from the nearest
    // access point before it that a reader of the same file remembered; gzip_reader.hpp).
    void seek(std::uint64_t offset);
    std::uint64_t position() const { return m_position; }
    bool compressed() const { return m_compressed; }
    std::uint64_t fileSize() const { return m_fileSize; }
    // The most bytes the uncompressed stream can hold (deflate expands at most ~1032:1).
    std::uint64_t maxUncompressedSize() const;
    const std::string& path() const { return m_path; }

  private:
    std::string m_path;
    void* m_gz = nullptr;                 // a plain file (zlib's direct reads)
    std::unique_ptr<GzipReader> m_reader; // a gzip file
    bool m_compressed = false;
    std::uint64_t m_fileSize = 0;
    std::uint64_t m_position = 0;
};

// The whole (uncompressed) file, or `length` bytes from `offset` (length 0 = to the end).
std::string readFileBytes(const std::string& path, std::uint64_t offset = 0,
                          std::uint64_t length = 0);

// The first up to n uncompressed bytes (for format detection); empty on an unreadable file.
std::string peekFileBytes(const std::string& path, std::size_t n);

} // namespace faultline::core
