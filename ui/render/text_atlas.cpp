#include "ui/render/text_atlas.hpp"

#include <stb_truetype.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace faultline::ui {

namespace {

struct RangeSpec {
    int first;
    int count;
};
// Printable ASCII, Latin-1 (micro, degree, superscripts, multiplication), en dash, minus sign.
constexpr RangeSpec kRanges[] = {{32, 95}, {160, 96}, {0x2013, 1}, {0x2212, 1}};

std::vector<unsigned char> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return {};
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

std::string defaultFontPath() {
    if (const char* env = std::getenv("FAULTLINE_FONT"); env && *env)
        return env;
    return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

std::vector<std::uint32_t> decodeUtf8(std::string_view s) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < s.size();) {
        const auto b = static_cast<unsigned char>(s[i]);
        int extra = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
        if (extra < 0 || i + static_cast<std::size_t>(extra) >= s.size()) {
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        std::uint32_t cp = extra == 0 ? b : b & (0x3F >> extra);
        bool ok = true;
        for (int k = 1; k <= extra; ++k) {
            const auto c = static_cast<unsigned char>(s[i + k]);
            if ((c >> 6) != 2) {
                ok = false;
                break;
            }
            cp = (cp << 6) | (c & 0x3F);
        }
        if (!ok) {
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        out.push_back(cp);
        i += static_cast<std::size_t>(extra) + 1;
    }
    return out;
}

std::optional<FontAtlas> FontAtlas::load(const std::string& ttfPath, float pixelHeight) {
    const std::vector<unsigned char> ttf = readFile(ttfPath);
    if (ttf.empty() || pixelHeight < 4.0f)
        return std::nullopt;
    stbtt_fontinfo info;
    if (!stbtt_InitFont(&info, ttf.data(), stbtt_GetFontOffsetForIndex(ttf.data(), 0)))
        return std::nullopt;

    FontAtlas atlas;
    atlas.m_pixelHeight = pixelHeight;
    int ascent = 0, descent = 0, gap = 0;
    stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
    const float scale = stbtt_ScaleForPixelHeight(&info, pixelHeight);
    atlas.m_ascent = ascent * scale;
    atlas.m_descent = -descent * scale;

    int glyphCount = 0;
    for (const RangeSpec& r : kRanges)
        glyphCount += r.count;
    // Square atlas, doubled until everything fits.
    int side = 128;
    while (double(side) * side < glyphCount * double(pixelHeight) * pixelHeight * 0.8)
        side *= 2;
    for (; side <= 8192; side *= 2) {
        std::vector<std::uint8_t> pixels(static_cast<std::size_t>(side) * side, 0);
        std::vector<stbtt_packedchar> packed(static_cast<std::size_t>(glyphCount));
        std::vector<stbtt_pack_range> ranges;
        std::size_t offset = 0;
        for (const RangeSpec& r : kRanges) {
            stbtt_pack_range pr{};
            pr.font_size = pixelHeight;
            pr.first_unicode_codepoint_in_range = r.first;
            pr.num_chars = r.count;
            pr.chardata_for_range = packed.data() + offset;
            ranges.push_back(pr);
            offset += static_cast<std::size_t>(r.count);
        }
        stbtt_pack_context ctx;
        if (!stbtt_PackBegin(&ctx, pixels.data(), side, side, 0, 1, nullptr))
            return std::nullopt;
        stbtt_PackSetOversampling(&ctx, 1, 1);
        const int ok = stbtt_PackFontRanges(&ctx, ttf.data(), 0, ranges.data(),
                                            static_cast<int>(ranges.size()));
        stbtt_PackEnd(&ctx);
        if (!ok)
            continue;
        atlas.m_width = atlas.m_height = side;
        atlas.m_alpha = std::move(pixels);
        offset = 0;
        for (const RangeSpec& r : kRanges) {
            atlas.m_ranges.push_back({r.first, r.count, offset});
            offset += static_cast<std::size_t>(r.count);
        }
        for (const stbtt_packedchar& c : packed)
            atlas.m_glyphs.push_back(
                {c.x0, c.y0, c.x1, c.y1, c.xoff, c.yoff, c.xadvance, c.xoff2, c.yoff2});
        return atlas;
    }
    return std::nullopt;
}

const FontAtlas::Glyph* FontAtlas::find(std::uint32_t cp) const {
    for (const Range& r : m_ranges) {
        if (cp >= std::uint32_t(r.first) && cp < std::uint32_t(r.first + r.count))
            return &m_glyphs[r.offset + (cp - r.first)];
    }
    return cp == '?' ? nullptr : find('?');
}

float FontAtlas::measure(std::string_view utf8) const {
    float w = 0.0f;
    for (std::uint32_t cp : decodeUtf8(utf8))
        if (const Glyph* g = find(cp))
            w += g->xadvance;
    return w;
}

void FontAtlas::layout(std::string_view utf8, float x, float y, std::vector<GlyphQuad>& out) const {
    float pen = x;
    const float baseline = std::round(y);
    for (std::uint32_t cp : decodeUtf8(utf8)) {
        const Glyph* g = find(cp);
        if (!g)
            continue;
        if (g->x1 > g->x0 && g->y1 > g->y0) {
            const float gx = std::round(pen + g->xoff);
            const float gy = std::round(baseline + g->yoff);
            const float w = float(g->x1 - g->x0), h = float(g->y1 - g->y0);
            out.push_back({gx, gy, gx + w, gy + h, g->x0 / float(m_width), g->y0 / float(m_height),
                           g->x1 / float(m_width), g->y1 / float(m_height)});
        }
        pen += g->xadvance;
    }
}

} // namespace faultline::ui
