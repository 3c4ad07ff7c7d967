// A small, bounded XML tokenizer for VTK files: tags with attributes, text, end of input.
// Comments, <?...?> and <!DOCTYPE> are skipped; nesting depth is bounded; tags must match.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

struct XmlAttribute {
    std::string_view name;
    std::string value; // the five predefined entities and character references decoded
};

class XmlTokenizer {
  public:
    enum class Kind { StartTag, EmptyTag, EndTag, Text, End };
    static constexpr std::size_t kMaxDepth = 64;
    static constexpr std::size_t kMaxAttributes = 64;

    // `path` names the file in errors; `text` must outlive the tokenizer.
    XmlTokenizer(const std::string& path, std::string_view text);

    // The next token. Throws InputError (path:line) on malformed markup, a mismatched or
    // missing end tag, nesting deeper than kMaxDepth, or text outside the root element.
    Kind next();

    std::string_view name() const { return m_name; } // of the current tag
    const std::vector<XmlAttribute>& attributes() const { return m_attributes; }
    const std::string* attribute(std::string_view name) const;
    std::string_view text() const { return m_text; } // Text: raw content, entities not decoded

    std::uint64_t line() const { return m_tokenLine; }   // where the current token starts
    std::size_t offset() const { return m_tokenOffset; } // byte offset of the token
    std::size_t position() const { return m_pos; }       // just past the current token
    std::size_t depth() const { return m_open.size(); }  // open elements after this token

    // Throws InputError at the current token's line.
    [[noreturn]] void fail(const std::string& message) const;

  private:
    [[noreturn]] void failAt(std::size_t offset, const std::string& message) const;
    void advanceTo(std::size_t pos); // moves m_pos, counting lines
    Kind readTag();
    std::size_t readName(std::size_t pos) const; // end of a name starting at pos
    std::string decodeEntities(std::string_view raw, std::size_t offset) const;

    struct Open {
        std::string_view name;
        std::uint64_t line;
    };
    const std::string& m_path;
    std::string_view m_data;
    std::size_t m_pos = 0;
    std::uint64_t m_line = 1;
    std::size_t m_tokenOffset = 0;
    std::uint64_t m_tokenLine = 1;
    std::vector<Open> m_open;
    bool m_rootClosed = false, m_rootSeen = false;
    std::string_view m_name, m_text;
    std::vector<XmlAttribute> m_attributes;
};

} // namespace faultline::core
