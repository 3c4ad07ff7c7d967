// TextLineReader: streams lines from a ByteSource with their byte offsets and numbers, and
// skips many lines at memchr speed (indexing multi-frame files without parsing them).
#pragma once

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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
    std::uint64_t lineNumber() const { return m_line; }             // lines consumed so far

  private:
    bool fill(); // makes room and reads more; false when nothing more
    ByteSource& m_source;
    std::string m_buffer;
    std::size_t m_pos = 0, m_end = 0;
    std::uint64_t m_bufferOffset = 0; // stream offset of m_buffer[0]
    std::uint64_t m_line = 0;
    bool m_eof = false;
};

// Lines of text already in memory (a frame's bytes), with the number of the last line given.
struct TextCursor {
    std::string_view text;
    std::size_t pos = 0;    // next unread byte
    std::uint64_t line = 0; // number of the last line given (start: the first line's - 1)
    // The next line without its '\n'; false at the end.
    bool next(std::string_view& out) {
        if (pos >= text.size())
            return false;
        std::size_t nl = text.find('\n', pos);
        if (nl == std::string_view::npos)
            nl = text.size();
        out = text.substr(pos, nl - pos);
        pos = nl + 1;
        ++line;
        return true;
    }
    std::size_t left() const { return text.size() - std::min(pos, text.size()); } // bytes
};

// Indexes a file of frames, each a header and then rows (blank lines between frames skipped):
// `header(reader, f, count)` reads frame number `count`'s header into f (offset and first line
// are set) and returns how many rows follow; `rowsOf(f, count)` names the frame in the error for
// a file that ends inside its rows ("particle rows of frame 3"). Throws InputError `none` when
// the file holds no frame.
// `partial` (optional): a file that ends inside a frame after complete ones (a run still writing,
// or stopped mid-write: a job's time limit) keeps the complete frames, and `partial` says what
// was left out; without it, or when no frame is complete, that is an error as any other.
template <class Index, class Header, class RowsOf>
std::vector<Index> indexTextFrames(const std::string& path, const std::string& none, Header header,
                                   RowsOf rowsOf, std::string* partial = nullptr) {
    ByteSource source(path);
    TextLineReader reader(source);
    std::vector<Index> frames;
    auto endsInside = [&](const std::string& where) {
        if (!partial || frames.empty())
            return false;
        const std::string n = std::to_string(frames.size());
        *partial = path + ": the file ends inside frame " + n + " (" + where +
                   "), as a run still " + "writing or stopped mid-write leaves it: the " + n +
                   " complete frames before it are read";
        return true;
    };
    for (;;) {
        Index f;
        std::uint64_t rows = 0, skipped = 0;
        try {
            reader.skipBlankLines();
            if (reader.atEnd())
                break;
            f.offset = reader.offset();
            f.firstLine = reader.lineNumber() + 1;
            rows = header(reader, f, frames.size());
            skipped = reader.skipLines(rows);
        } catch (const TruncatedInput& e) {
            if (endsInside(e.message() + " at byte " + std::to_string(e.position())))
                break;
            throw;
        } catch (const InputError&) {
            // A header cut short by the end of the file (or by a compressed stream's cut, met
            // while looking for what follows it).
            bool atEnd = true;
            try {
                atEnd = reader.atEnd();
            } catch (const TruncatedInput&) {
            }
            if (atEnd &&
                endsInside("its header stops at line " + std::to_string(reader.lineNumber())))
                break;
            throw;
        }
        if (skipped < rows) {
            const std::string what =
                "file ends after " + std::to_string(skipped) + " of " + rowsOf(f, frames.size());
            if (endsInside("line " + std::to_string(reader.lineNumber() + 1) + ": " + what))
                break;
            throw InputError(path, InputError::Where::Line, reader.lineNumber() + 1, what);
        }
        f.length = reader.offset() - f.offset;
        frames.push_back(f);
    }
    if (frames.empty())
        throw InputError(path, none);
    return frames;
}

} // namespace faultline::core
