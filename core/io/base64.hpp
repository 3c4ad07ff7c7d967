// Streaming base64 decoder for VTK XML binary data. Blanks are skipped and '=' padding may end
// any 4-character group: VTK encodes a block's header and its data separately.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace faultline::core {

class Base64Decoder {
  public:
    explicit Base64Decoder(std::string_view text) : m_text(text) {}

    // Decodes up to `n` bytes into dst; returns how many it wrote (fewer at the end of the text
    // or on an error: check failed()).
    std::size_t decode(unsigned char* dst, std::size_t n);

    bool failed() const { return !m_error.empty(); }
    const std::string& error() const { return m_error; }
    std::size_t errorOffset() const { return m_errorOffset; } // in the text
    std::size_t position() const { return m_pos; }            // characters consumed
    // The most bytes the rest of the text can decode to.
    std::size_t maxRemainingBytes() const {
        return (m_text.size() - m_pos) / 4 * 3 + (m_pendingCount - m_pendingUsed);
    }

  private:
    bool nextGroup(); // decodes one group of 4 characters into m_pending
    std::string_view m_text;
    std::size_t m_pos = 0;
    unsigned char m_pending[3] = {0, 0, 0};
    std::size_t m_pendingCount = 0, m_pendingUsed = 0;
    std::string m_error;
    std::size_t m_errorOffset = 0;
};

// Decodes all of `text`; false (with the error and its offset in the text) on bad base64.
bool decodeBase64(std::string_view text, std::string& out, std::string& error,
                  std::size_t& errorOffset);

} // namespace faultline::core

namespace faultline::core {

// Standard base64 with '=' padding (what decodeBase64 reads back).
std::string encodeBase64(std::string_view bytes);

} // namespace faultline::core
