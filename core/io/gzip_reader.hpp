// GzipReader: the uncompressed stream of a gzip file, read in order or from any offset. zlib's
// own gzseek inflates from the start of the file to reach an offset, so each frame of a
// multi-frame dump.gz cost as much as all the frames before it (the demo's frame 34: 1.3 s, its
// frame 0: 75 ms). Here, as a reader inflates, it remembers access points every few MB of output
// (a deflate block's start: its bit offset in the file and the 32 KB of output before it, the
// window the block may refer back to) in an index shared by every reader of the same file (path,
// size and modification time), so a seek inflates from the nearest point before the offset: at
// most a spacing (4 MB or more) of data, whichever reader passed there first (the one that indexed
// the frames when the file was opened, usually).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace faultline::core {

namespace detail {
struct GzipIndex;
struct GzipAccessPoint;
// Tests: the smallest spacing of access points in uncompressed bytes (0: the default, 4 MiB),
// and forgetting every file's access points.
void setGzipIndexSpacing(std::uint64_t bytes);
void clearGzipIndexes();
// How many access points the index of this file holds now (tests).
std::size_t gzipAccessPoints(const std::string& path);
} // namespace detail

class GzipReader {
  public:
    // `path` must start with the gzip magic; throws InputError when it cannot be opened.
    GzipReader(const std::string& path, std::uint64_t fileSize);
    ~GzipReader();
    GzipReader(const GzipReader&) = delete;
    GzipReader& operator=(const GzipReader&) = delete;

    // Up to n bytes of the uncompressed stream; 0 at its end. Members of a concatenated gzip
    // file follow each other; anything after the last member that is no gzip member is ignored
    // (as gzread does). Throws InputError (byte offset in the uncompressed stream) on corrupt
    // data, TruncatedInput where the stream stops short.
    std::size_t read(char* dst, std::size_t n);
    // Positions at `offset` of the uncompressed stream. Past its end: reads return 0.
    void seek(std::uint64_t offset);
    std::uint64_t position() const { return m_out; }

  private:
    enum class Mode { Gzip, Raw }; // a member from its header; raw deflate from an access point
    void openAt(std::uint64_t fileOffset);
    bool ensureInput(std::size_t bytes);
    void restart();
    void restore(const detail::GzipAccessPoint& point);
    bool endOfMember(); // false: the file stops inside the member's trailer
    void remember();
    void skip(std::uint64_t bytes);
    void note(const unsigned char* out, std::size_t produced);
    [[noreturn]] void fail(const std::string& what) const;
    [[noreturn]] void failTruncated() const; // TruncatedInput

    std::string m_path;
    std::FILE* m_file = nullptr;
    void* m_stream = nullptr; // z_stream
    Mode m_mode = Mode::Gzip;
    bool m_end = false;       // past the last member
    bool m_fileEnd = false;   // nothing more to read from the file
    bool m_truncated = false; // the stream stopped short: the next read throws
    std::vector<unsigned char> m_in;
    std::uint64_t m_inOffset = 0; // file offset of m_in[0]
    std::uint64_t m_out = 0;      // uncompressed bytes before the next one read
    std::uint64_t m_memberStart = 0;
    std::uint64_t m_nextPoint = 0;     // no access point is wanted before this output offset
    std::vector<unsigned char> m_ring; // the last 32 KB of output
    std::shared_ptr<detail::GzipIndex> m_index;
};

} // namespace faultline::core
