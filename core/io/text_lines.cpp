#include "core/io/text_lines.hpp"

#include "core/io/input_error.hpp"
#include "core/io/newline_count.hpp"

#include <cstring>

namespace faultline::core {

namespace {
constexpr std::size_t kBlock = 4u << 20;
}

TextLineReader::TextLineReader(ByteSource& source) : m_source(source) {
    m_buffer.resize(kBlock);
    m_bufferOffset = source.position();
}

bool TextLineReader::fill() {
    if (m_eof)
        return false;
    if (m_pos > 0) {
        std::memmove(m_buffer.data(), m_buffer.data() + m_pos, m_end - m_pos);
        m_bufferOffset += m_pos;
        m_end -= m_pos;
        m_pos = 0;
    }
    if (m_end == m_buffer.size())
        m_buffer.resize(m_buffer.size() * 2);
    const std::size_t got = m_source.read(m_buffer.data() + m_end, m_buffer.size() - m_end);
    if (got == 0) {
        m_eof = true;
        return false;
    }
    m_end += got;
    return true;
}

bool TextLineReader::next(std::string_view& line) {
    for (;;) {
        const char* start = m_buffer.data() + m_pos;
        const void* nl = std::memchr(start, '\n', m_end - m_pos);
        if (nl || (m_eof && m_pos < m_end)) {
            const std::size_t len =
                nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - start) : m_end - m_pos;
            if (std::memchr(start, '\0', len))
                throw InputError(
                    m_source.path(), InputError::Where::Byte,
                    offset() + static_cast<std::size_t>(
                                   static_cast<const char*>(std::memchr(start, '\0', len)) - start),
                    "binary data (a NUL byte) where text was expected");
            line = std::string_view(start, len);
            m_pos += len + (nl ? 1 : 0);
            ++m_line;
            return true;
        }
        if (m_end - m_pos > kMaxLineBytes)
            throw InputError(m_source.path(), InputError::Where::Line, m_line + 1,
                             "line longer than 1 MiB: not a text particle file");
        if (!fill())
            return false;
    }
}

std::uint64_t TextLineReader::skipLines(std::uint64_t count) {
    std::uint64_t skipped = 0;
    bool midLine = false; // consumed bytes of a line whose '\n' is not yet seen
    while (skipped < count) {
        if (m_pos == m_end && !fill())
            break;
        const char* p = m_buffer.data() + m_pos;
        const char* end = m_buffer.data() + m_end;
        // Whole buffers that end before the wanted line are counted, not walked line by line.
        if (const std::size_t inBuffer = countNewlines(p, end); skipped + inBuffer < count) {
            skipped += inBuffer;
            midLine = end > p && end[-1] != '\n';
            m_pos = m_end;
            continue;
        }
        while (skipped < count && p < end) {
            const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
            if (!nl) {
                p = end;
                midLine = true;
                break;
            }
            p = static_cast<const char*>(nl) + 1;
            ++skipped;
            midLine = false;
        }
        m_pos = static_cast<std::size_t>(p - m_buffer.data());
    }
    if (skipped < count && midLine)
        ++skipped; // the last line of the file has no '\n'
    m_line += skipped;
    return skipped;
}

void TextLineReader::skipBlankLines() {
    for (;;) {
        if (m_pos == m_end && !fill())
            return;
        std::size_t p = m_pos;
        while (p < m_end && (m_buffer[p] == ' ' || m_buffer[p] == '\t' || m_buffer[p] == '\r'))
            ++p;
        if (p == m_end) {
            if (m_eof) {
                m_pos = p;
                return;
            }
            if (!fill() && m_pos == m_end)
                return;
            continue;
        }
        if (m_buffer[p] != '\n')
            return;
        m_pos = p + 1;
        ++m_line;
    }
}

bool TextLineReader::atEnd() {
    if (m_pos < m_end)
        return false;
    return !fill();
}

} // namespace faultline::core
