#include "core/io/input_error.hpp"

namespace faultline::core {

namespace {
std::string compose(const std::string& path, InputError::Where where, std::uint64_t position,
                    const std::string& message) {
    switch (where) {
    case InputError::Where::Line:
        return path + ":" + std::to_string(position) + ": " + message;
    case InputError::Where::Byte:
        return path + ": byte " + std::to_string(position) + ": " + message;
    case InputError::Where::File:
        break;
    }
    return path + ": " + message;
}
} // namespace

InputError::InputError(std::string path, const std::string& message)
    : std::runtime_error(compose(path, Where::File, 0, message)), m_path(std::move(path)),
      m_message(message) {}

InputError::InputError(std::string path, Where where, std::uint64_t position,
                       const std::string& message)
    : std::runtime_error(compose(path, where, position, message)), m_path(std::move(path)),
      m_where(where), m_position(position), m_message(message) {}

std::string quoteForError(std::string_view text, std::size_t maxLength) {
    std::string out = "'";
    for (std::size_t i = 0; i < text.size() && i < maxLength; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c >= 32 && c < 127) {
            out += static_cast<char>(c);
        } else {
            static const char* kHex = "0123456789abcdef";
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    if (text.size() > maxLength)
        out += "...";
    out += "'";
    return out;
}

} // namespace faultline::core
