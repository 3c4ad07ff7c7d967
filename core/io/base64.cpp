#include "core/io/base64.hpp"

#include "core/io/input_error.hpp"

#include <array>

namespace faultline::core {

namespace {

constexpr unsigned char kBad = 0xFF, kPad = 0xFE, kBlank = 0xFD;

constexpr std::array<unsigned char, 256> makeTable() {
    std::array<unsigned char, 256> t{};
    for (auto& v : t)
        v = kBad;
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (unsigned char i = 0; i < 64; ++i)
        t[static_cast<unsigned char>(alphabet[i])] = i;
    t['='] = kPad;
    for (char c : {' ', '\t', '\n', '\r', '\f', '\v'})
        t[static_cast<unsigned char>(c)] = kBlank;
    return t;
}
constexpr std::array<unsigned char, 256> kTable = makeTable();

} // namespace

bool Base64Decoder::nextGroup() {
    unsigned char v[4];
    std::size_t have = 0, pads = 0;
    while (have < 4) {
        while (m_pos < m_text.size() && kTable[static_cast<unsigned char>(m_text[m_pos])] == kBlank)
            ++m_pos;
        if (m_pos >= m_text.size()) {
            if (have == 0)
                return false;
            m_error = "base64 data ends inside a group of 4 characters";
            m_errorOffset = m_pos;
            return false;
        }
        const unsigned char c = kTable[static_cast<unsigned char>(m_text[m_pos])];
        if (c == kBad) {
            m_error = "expected base64 data, found " + quoteForError(m_text.substr(m_pos, 1));
            m_errorOffset = m_pos;
            return false;
        }
        if (c == kPad) {
            if (have < 2) {
                m_error = "misplaced '=' padding in base64 data";
                m_errorOffset = m_pos;
                return false;
            }
            ++pads;
            v[have++] = 0;
        } else {
            if (pads > 0) {
                m_error = "base64 data continues inside a padded group";
                m_errorOffset = m_pos;
                return false;
            }
            v[have++] = c;
        }
        ++m_pos;
    }
    m_pending[0] = static_cast<unsigned char>((v[0] << 2) | (v[1] >> 4));
    m_pending[1] = static_cast<unsigned char>((v[1] << 4) | (v[2] >> 2));
    m_pending[2] = static_cast<unsigned char>((v[2] << 6) | v[3]);
    m_pendingCount = 3 - pads;
    m_pendingUsed = 0;
    return true;
}

std::size_t Base64Decoder::decode(unsigned char* dst, std::size_t n) {
    std::size_t written = 0;
    while (written < n && !failed()) {
        if (m_pendingUsed < m_pendingCount) {
            dst[written++] = m_pending[m_pendingUsed++];
            continue;
        }
        m_pendingCount = m_pendingUsed = 0;
        if (!nextGroup())
            break;
    }
    return written;
}

bool decodeBase64(std::string_view text, std::string& out, std::string& error,
                  std::size_t& errorOffset) {
    Base64Decoder decoder(text);
    out.resize(decoder.maxRemainingBytes());
    const std::size_t n = decoder.decode(reinterpret_cast<unsigned char*>(out.data()), out.size());
    out.resize(n);
    if (decoder.failed()) {
        error = decoder.error();
        errorOffset = decoder.errorOffset();
        return false;
    }
    return true;
}

} // namespace faultline::core

namespace faultline::core {

std::string encodeBase64(std::string_view bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 |
                           static_cast<unsigned char>(bytes[i + 1]) << 8 |
                           static_cast<unsigned char>(bytes[i + 2]);
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        if (rest == 2)
            v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

} // namespace faultline::core
