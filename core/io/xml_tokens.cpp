#include "core/io/xml_tokens.hpp"

#include "core/io/input_error.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace faultline::core {

namespace {

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
inline bool isNameStart(char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u >= 'A' && u <= 'Z') || (u >= 'a' && u <= 'z') || u == '_' || u == ':' || u >= 0x80;
}
inline bool isNameChar(char c) {
    return isNameStart(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
}

void appendUtf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

} // namespace

XmlTokenizer::XmlTokenizer(const std::string& path, std::string_view text)
    : m_path(path), m_data(text) {
    if (m_data.substr(0, 3) == "\xEF\xBB\xBF")
        m_pos = 3; // UTF-8 byte order mark
}

const std::string* XmlTokenizer::attribute(std::string_view name) const {
    for (const auto& a : m_attributes)
        if (a.name == name)
            return &a.value;
    return nullptr;
}

void XmlTokenizer::fail(const std::string& message) const {
    throw InputError(m_path, InputError::Where::Line, m_tokenLine, message);
}

void XmlTokenizer::failAt(std::size_t offset, const std::string& message) const {
    offset = std::min(offset, m_data.size());
    std::uint64_t line = m_line;
    if (offset >= m_pos)
        line += static_cast<std::uint64_t>(
            std::count(m_data.begin() + static_cast<std::ptrdiff_t>(m_pos),
                       m_data.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    throw InputError(m_path, InputError::Where::Line, line, message);
}

void XmlTokenizer::advanceTo(std::size_t pos) {
    m_line += static_cast<std::uint64_t>(
        std::count(m_data.begin() + static_cast<std::ptrdiff_t>(m_pos),
                   m_data.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
    m_pos = pos;
}

std::size_t XmlTokenizer::readName(std::size_t pos) const {
    if (pos >= m_data.size() || !isNameStart(m_data[pos]))
        return pos;
    while (pos < m_data.size() && isNameChar(m_data[pos]))
        ++pos;
    return pos;
}

std::string XmlTokenizer::decodeEntities(std::string_view raw, std::size_t offset) const {
    if (raw.find('&') == std::string_view::npos)
        return std::string(raw);
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] != '&') {
            out += raw[i];
            continue;
        }
        const std::size_t semi = raw.find(';', i);
        if (semi == std::string_view::npos || semi - i > 12)
            failAt(offset + i, "expected an entity such as &amp; or &#38; after '&'");
        const std::string_view e = raw.substr(i + 1, semi - i - 1);
        if (e == "lt")
            out += '<';
        else if (e == "gt")
            out += '>';
        else if (e == "amp")
            out += '&';
        else if (e == "quot")
            out += '"';
        else if (e == "apos")
            out += '\'';
        else if (e.size() >= 2 && e[0] == '#') {
            const bool hex = e[1] == 'x' || e[1] == 'X';
            std::uint32_t cp = 0;
            const char* b = e.data() + (hex ? 2 : 1);
            auto r = std::from_chars(b, e.data() + e.size(), cp, hex ? 16 : 10);
            if (r.ec != std::errc() || r.ptr != e.data() + e.size() || cp == 0 || cp > 0x10FFFF)
                failAt(offset + i,
                       "bad character reference " + quoteForError(raw.substr(i, semi - i + 1)));
            appendUtf8(out, cp);
        } else {
            failAt(offset + i, "unknown entity " + quoteForError(raw.substr(i, semi - i + 1)));
        }
        i = semi;
    }
    return out;
}

XmlTokenizer::Kind XmlTokenizer::next() {
    for (;;) {
        m_tokenOffset = m_pos;
        m_tokenLine = m_line;
        m_attributes.clear();
        m_name = {};
        m_text = {};
        if (m_pos >= m_data.size()) {
            if (!m_open.empty())
                failAt(m_pos, "the file ends inside <" + std::string(m_open.back().name) +
                                  "> opened at line " + std::to_string(m_open.back().line) +
                                  ": expected </" + std::string(m_open.back().name) + ">");
            if (!m_rootSeen)
                fail("no XML element found");
            return Kind::End;
        }
        if (m_data[m_pos] != '<') {
            const void* lt = std::memchr(m_data.data() + m_pos, '<', m_data.size() - m_pos);
            const std::size_t end =
                lt ? static_cast<std::size_t>(static_cast<const char*>(lt) - m_data.data())
                   : m_data.size();
            m_text = m_data.substr(m_pos, end - m_pos);
            if (m_open.empty()) {
                for (std::size_t i = 0; i < m_text.size(); ++i)
                    if (!isBlank(m_text[i]))
                        failAt(m_pos + i,
                               std::string(m_rootClosed ? "content after" : "text before") +
                                   " the root element: " + quoteForError(m_text.substr(i)));
                advanceTo(end);
                continue;
            }
            advanceTo(end);
            return Kind::Text;
        }
        const std::string_view rest = m_data.substr(m_pos);
        if (rest.substr(0, 4) == "<!--") {
            const std::size_t close = rest.find("-->", 4);
            if (close == std::string_view::npos)
                fail("unterminated comment: expected '-->'");
            advanceTo(m_pos + close + 3);
            continue;
        }
        if (rest.substr(0, 2) == "<?") {
            const std::size_t close = rest.find("?>", 2);
            if (close == std::string_view::npos)
                fail("unterminated processing instruction: expected '?>'");
            advanceTo(m_pos + close + 2);
            continue;
        }
        if (rest.substr(0, 9) == "<![CDATA[") {
            const std::size_t close = rest.find("]]>", 9);
            if (close == std::string_view::npos)
                fail("unterminated CDATA section: expected ']]>'");
            if (m_open.empty())
                fail("CDATA outside the root element");
            m_text = rest.substr(9, close - 9);
            advanceTo(m_pos + close + 3);
            return Kind::Text;
        }
        if (rest.substr(0, 2) == "<!") {
            const std::size_t close = rest.find('>', 2);
            if (close == std::string_view::npos ||
                rest.substr(2, close - 2).find('[') != std::string_view::npos)
                fail("unsupported or unterminated declaration " +
                     quoteForError(rest.substr(0, 20)));
            advanceTo(m_pos + close + 1);
            continue;
        }
        return readTag();
    }
}

XmlTokenizer::Kind XmlTokenizer::readTag() {
    const bool closing = m_pos + 1 < m_data.size() && m_data[m_pos + 1] == '/';
    const std::size_t nameStart = m_pos + (closing ? 2 : 1);
    const std::size_t nameEnd = readName(nameStart);
    if (nameEnd == nameStart)
        failAt(nameStart,
               "expected a tag name after '<', found " +
                   (nameStart < m_data.size() ? quoteForError(m_data.substr(nameStart, 10))
                                              : std::string("the end of the file")));
    m_name = m_data.substr(nameStart, nameEnd - nameStart);
    std::size_t p = nameEnd;
    auto skipBlanks = [&] {
        while (p < m_data.size() && isBlank(m_data[p]))
            ++p;
    };
    if (closing) {
        skipBlanks();
        if (p >= m_data.size() || m_data[p] != '>')
            failAt(p, "expected '>' to end </" + std::string(m_name) + ">");
        if (m_open.empty())
            fail("unexpected </" + std::string(m_name) + ">: no element is open");
        if (m_open.back().name != m_name)
            fail("expected </" + std::string(m_open.back().name) + "> (opened at line " +
                 std::to_string(m_open.back().line) + "), found </" + std::string(m_name) + ">");
        m_open.pop_back();
        if (m_open.empty())
            m_rootClosed = true;
        advanceTo(p + 1);
        return Kind::EndTag;
    }
    if (m_rootClosed)
        fail("content after the root element: <" + std::string(m_name) + ">");
    for (;;) {
        const std::size_t before = p;
        skipBlanks();
        if (p >= m_data.size())
            failAt(p, "the file ends inside the tag <" + std::string(m_name) + ">");
        if (m_data[p] == '>' || (m_data[p] == '/' && p + 1 < m_data.size() && m_data[p + 1] == '>'))
            break;
        if (p == before)
            failAt(p, "expected a blank, '>' or '/>' in <" + std::string(m_name) + ">, found " +
                          quoteForError(m_data.substr(p, 10)));
        const std::size_t attrEnd = readName(p);
        if (attrEnd == p)
            failAt(p, "expected an attribute name in <" + std::string(m_name) + ">, found " +
                          quoteForError(m_data.substr(p, 10)));
        const std::string_view attrName = m_data.substr(p, attrEnd - p);
        p = attrEnd;
        skipBlanks();
        if (p >= m_data.size() || m_data[p] != '=')
            failAt(p, "expected '=' after attribute " + std::string(attrName));
        ++p;
        skipBlanks();
        if (p >= m_data.size() || (m_data[p] != '"' && m_data[p] != '\''))
            failAt(p, "expected a quoted value for attribute " + std::string(attrName));
        const char quote = m_data[p];
        const std::size_t valueStart = p + 1;
        const std::size_t valueEnd = m_data.find(quote, valueStart);
        if (valueEnd == std::string_view::npos)
            failAt(p, "unterminated value of attribute " + std::string(attrName));
        const std::string_view raw = m_data.substr(valueStart, valueEnd - valueStart);
        if (raw.find('<') != std::string_view::npos)
            failAt(valueStart + raw.find('<'),
                   "'<' inside the value of attribute " + std::string(attrName));
        if (attribute(attrName))
            failAt(p, "attribute " + std::string(attrName) + " appears twice");
        if (m_attributes.size() >= kMaxAttributes)
            failAt(p, "more than " + std::to_string(kMaxAttributes) + " attributes in <" +
                          std::string(m_name) + ">");
        m_attributes.push_back({attrName, decodeEntities(raw, valueStart)});
        p = valueEnd + 1;
    }
    const bool empty = m_data[p] == '/';
    if (!empty) {
        if (m_open.size() >= kMaxDepth)
            fail("XML elements nested deeper than " + std::to_string(kMaxDepth) + " levels");
        m_open.push_back({m_name, m_tokenLine});
    } else if (m_open.empty()) {
        m_rootClosed = true;
    }
    m_rootSeen = true;
    advanceTo(p + (empty ? 2 : 1));
    return empty ? Kind::EmptyTag : Kind::StartTag;
}

} // namespace faultline::core
