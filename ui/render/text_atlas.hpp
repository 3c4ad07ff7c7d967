// Text for in-image labels (legend ticks and titles): a TrueType font (DejaVu Sans by default)
// baked into an 8-bit alpha atlas at one pixel size with stb_truetype, and laid out as quads.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::ui {

// One glyph's screen rectangle (pixels, y down) and atlas coordinates (0..1).
struct GlyphQuad {
    float x0, y0, x1, y1;
    float u0, v0, u1, v1;
};

class FontAtlas {
  public:
    // Bakes printable ASCII, Latin-1 and a few symbols (minus sign, en dash) at `pixelHeight`.
    // nullopt when the file cannot be read or is not a TrueType font.
    static std::optional<FontAtlas> load(const std::string& ttfPath, float pixelHeight);

    float pixelHeight() const { return m_pixelHeight; }
    float ascent() const { return m_ascent; }   // pixels above the baseline
    float descent() const { return m_descent; } // pixels below the baseline (positive)
    int width() const { return m_width; }
    int height() const { return m_height; }
    const std::vector<std::uint8_t>& alpha() const { return m_alpha; }

    // Width in pixels of a UTF-8 string; characters not baked count as '?'.
    float measure(std::string_view utf8) const;
    // Appends a quad per visible glyph, the pen starting at x on the baseline y (pixels, y down).
    // Quads are snapped to whole pixels so small text stays crisp.
    void layout(std::string_view utf8, float x, float y, std::vector<GlyphQuad>& out) const;

  private:
    struct Glyph {
        std::uint16_t x0, y0, x1, y1; // atlas rectangle
        float xoff, yoff, xadvance, xoff2, yoff2;
    };
    struct Range {
        int first;
        int count;
        std::size_t offset; // into m_glyphs
    };
    float m_pixelHeight = 0, m_ascent = 0, m_descent = 0;
    int m_width = 0, m_height = 0;
    std::vector<std::uint8_t> m_alpha;
    std::vector<Glyph> m_glyphs;
    std::vector<Range> m_ranges;
    const Glyph* find(std::uint32_t codepoint) const;
};

// FAULTLINE_FONT if set, else DejaVu Sans from the usual Debian folder.
std::string defaultFontPath();

// Decodes UTF-8 (invalid bytes become U+FFFD).
std::vector<std::uint32_t> decodeUtf8(std::string_view s);

} // namespace faultline::ui
