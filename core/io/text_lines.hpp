// TextLineReader: streams lines from a ByteSource with their byte offsets and numbers, and
// skips many lines at memchr speed (indexing multi-frame files without parsing them).
#pragma once

#include "core/io/byte_source.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace faultline::core {

class TextLineReader {
  public:
    static constexpr std::size_t kMaxLineBytes = 1u << 20;

    explicit TextLineReader(ByteSource& source);

    // The next line without its '\n' (valid until the next call). False at the end.
    // Throws InputError on a line longer than kMaxLineBytes or a NUL byte (binary data).
    bool next(std::string_view& line);
    // Skips up to `count` lines; returns how many it skipped.
    std::uint64_t skipLines(std::uint64_t count);
    // Skips lines holding only blanks.
    void skipBlankLines();
    bool atEnd();

    std::uint64_t offset() const { return m_bufferOffset + m_pos; } // next unread byte
    std::uint64_t lineNumber() const { return m_line; }              // lines consumed so far

  private:
    bool fill(); // makes room and reads more; false when nothing more
    ByteSource& m_source;
    std::string m_buffer;
    std::size_t m_pos = 0, m_end = 0;
    std::uint64_t m_bufferOffset = 0; // stream offset of m_buffer[0]
    std::uint64_t m_line = 0;
    bool m_eof = false;
};

} // namespace faultline::core
