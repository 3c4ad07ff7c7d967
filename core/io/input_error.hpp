// InputError: what went wrong reading user data, and where (path, line or byte offset).
// Every reader and loader throws this on bad input; callers show what() to the user as it is.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace faultline::core {

class InputError : public std::runtime_error {
  public:
    enum class Where { File, Line, Byte };

    // "path: message"
    InputError(std::string path, const std::string& message);
    // "path:line: message" (lines count from 1) or "path: byte N: message"
    InputError(std::string path, Where where, std::uint64_t position, const std::string& message);

    const std::string& path() const { return m_path; }
    Where where() const { return m_where; }
    std::uint64_t position() const { return m_position; }
    const std::string& message() const { return m_message; }

  private:
    std::string m_path;
    Where m_where = Where::File;
    std::uint64_t m_position = 0;
    std::string m_message;
};

// The input stops early: a compressed stream cut short (a file still being written, or a copy or
// run stopped mid-write). Readers that can keep what came before it catch this one.
class TruncatedInput : public InputError {
  public:
    using InputError::InputError;
};

// Shortens user-provided text (a bad token) for an error message.
std::string quoteForError(std::string_view text, std::size_t maxLength = 40);

} // namespace faultline::core
