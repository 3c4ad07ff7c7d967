// GlRenderer, second half: the composite (contact darkening, down-sampling), box handles, the
// legend, and reading the image back.
#include "ui/render/gl_renderer.hpp"

#include "core/color/legend_ticks.hpp"
#include "ui/render/legend_layout.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace faultline::ui {

namespace {

constexpr GLuint kUnitSource = 0, kUnitDepth = 1, kUnitFont = 4, kUnitColorMap = 3,
                 kUnitOcclusion = 5, kUnitContext = 6;
constexpr GLuint kUnitSpheres = 0, kUnitRows = 2;

// Handle colours by axis (x red, y green, z blue), and the one being dragged.
constexpr glm::vec3 kHandleColors[3] = {
    {0.86f, 0.24f, 0.20f}, {0.24f, 0.66f, 0.30f}, {0.22f, 0.42f, 0.86f}};
constexpr glm::vec3 kActiveHandle{1.0f, 0.80f, 0.15f};

struct OverlayVertex {
    float x, y, u, v, r, g, b, a;
};

void addQuad(std::vector<OverlayVertex>& out, float x0, float y0, float x1, float y1, float u0,
             float v0, float u1, float v1, glm::vec4 c) {
    const OverlayVertex a{x0, y0, u0, v0, c.r, c.g, c.b, c.a};
    const OverlayVertex b{x1, y0, u1, v0, c.r, c.g, c.b, c.a};
    const OverlayVertex d{x0, y1, u0, v1, c.r, c.g, c.b, c.a};
    const OverlayVertex e{x1, y1, u1, v1, c.r, c.g, c.b, c.a};
    out.insert(out.end(), {a, b, d, d, b, e});
}

void addRect(std::vector<OverlayVertex>& out, const LegendRect& r, glm::vec4 c) {
    addQuad(out, r.x0, r.y0, r.x1, r.y1, 0, 0, 0, 0, c);
}

} // namespace

void GlRenderer::composite(const FrameSetup& f, const RenderTarget& target) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0 + kUnitSource);
    glBindTexture(GL_TEXTURE_2D, m_scene.color());
    glActiveTexture(GL_TEXTURE0 + kUnitDepth);
    glBindTexture(GL_TEXTURE_2D, m_scene.depth());
    const double radius =
        m_x.empty() ? std::max(sceneBounds().radius * 0.01, 1e-9) : m_typicalRadius;
    auto setDepthUniforms = [&](GLuint p) {
        glUniform1i(gl::uniformLocation(p, "uDepth"), kUnitDepth);
        glUniform2f(gl::uniformLocation(p, "uNearFar"), float(f.clip.nearClip),
                    float(f.clip.farClip));
        glUniform1i(gl::uniformLocation(p, "uPerspective"), f.perspective ? 1 : 0);
        glUniform1f(gl::uniformLocation(p, "uWorldRadius"), float(radius));
    };
    if (m_style.ambientOcclusion) {
        glBindFramebuffer(GL_FRAMEBUFFER, m_occlusion.framebuffer());
        glViewport(0, 0, m_occlusion.width(), m_occlusion.height());
        const GLuint p = m_programs.occlusion.id();
        glUseProgram(p);
        setDepthUniforms(p);
        // Pixels per world unit at unit view depth (perspective) or anywhere (orthographic).
        glUniform1f(gl::uniformLocation(p, "uPixelsPerUnit"),
                    float(f.projection[1][1] * 0.5 * f.height));
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glActiveTexture(GL_TEXTURE0 + kUnitOcclusion);
        glBindTexture(GL_TEXTURE_2D, m_occlusion.color());
    }
    const gl::RenderTexture& dst = f.supersample > 1 ? m_composite : m_output;
    glBindFramebuffer(GL_FRAMEBUFFER, dst.framebuffer());
    glViewport(0, 0, f.width, f.height);
    GLuint p = m_programs.composite.id();
    glUseProgram(p);
    setDepthUniforms(p);
    glUniform1i(gl::uniformLocation(p, "uColor"), kUnitSource);
    glUniform1i(gl::uniformLocation(p, "uOcclusion"), kUnitOcclusion);
    glUniform1i(gl::uniformLocation(p, "uAmbientOcclusion"), m_style.ambientOcclusion ? 1 : 0);
    glUniform1f(gl::uniformLocation(p, "uStrength"), std::clamp(m_style.aoStrength, 0.0f, 1.0f));
    const bool context = m_stats.contextPoints > 0;
    glUniform1f(gl::uniformLocation(p, "uContextAlpha"),
                context ? std::clamp(m_style.contextColor.a, 0.0f, 1.0f) : 0.0f);
    if (context) {
        glActiveTexture(GL_TEXTURE0 + kUnitContext);
        glBindTexture(GL_TEXTURE_2D, m_contextLayer.color());
        glUniform1i(gl::uniformLocation(p, "uContext"), kUnitContext);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);

    if (f.supersample > 1) {
        glBindFramebuffer(GL_FRAMEBUFFER, m_output.framebuffer());
        glViewport(0, 0, target.width, target.height);
        p = m_programs.downsample.id();
        glUseProgram(p);
        glActiveTexture(GL_TEXTURE0 + kUnitSource);
        glBindTexture(GL_TEXTURE_2D, m_composite.color());
        glUniform1i(gl::uniformLocation(p, "uSource"), kUnitSource);
        glUniform1i(gl::uniformLocation(p, "uFactor"), f.supersample);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

void GlRenderer::drawHandles(const FrameSetup& f) {
    m_stats.handles = 0;
    if (!m_selected)
        return;
    useSphereProgram(f);
    const GLuint p =
        f.perspective ? m_programs.spheresPerspective.id() : m_programs.spheresOrthographic.id();
    glUniform1i(gl::uniformLocation(p, "uColorMode"), 0);
    m_handleSpheresTex.bind(kUnitSpheres);
    m_handleRowsTex.bind(kUnitRows);
    glEnable(GL_DEPTH_TEST);
    for (int face = 0; face < 6; ++face) {
        const bool active = m_selected->activeFace == static_cast<core::BoxFace>(face);
        const glm::vec3 c = active ? kActiveHandle : kHandleColors[face / 2];
        glUniform3fv(gl::uniformLocation(p, "uColor"), 1, glm::value_ptr(c));
        glDrawArrays(GL_TRIANGLES, 3 * face, 3);
    }
    m_stats.handles = 6;
}

GlRenderer::FontTexture* GlRenderer::font(int pixelHeight) {
    auto it = m_fonts.find(pixelHeight);
    if (it != m_fonts.end())
        return it->second.get();
    std::unique_ptr<FontTexture> entry;
    if (auto atlas = FontAtlas::load(defaultFontPath(), float(pixelHeight))) {
        entry = std::make_unique<FontTexture>(FontTexture{std::move(*atlas), gl::makeTexture()});
        glBindTexture(GL_TEXTURE_2D, entry->texture.id());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, entry->atlas.width(), entry->atlas.height(), 0,
                     GL_RED, GL_UNSIGNED_BYTE, entry->atlas.alpha().data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_2D, 0);
    } else if (!m_fontMissingReported) {
        std::fprintf(stderr, "faultline: cannot load the font %s; legends have no text\n",
                     defaultFontPath().c_str());
        m_fontMissingReported = true;
    }
    FontTexture* raw = entry.get();
    m_fonts[pixelHeight] = std::move(entry);
    return raw;
}

void GlRenderer::drawLegend(const RenderTarget& target) {
    m_stats.legendTicks = 0;
    const bool categories = m_style.showLegend && !m_style.categories.empty();
    const bool legend = m_style.showLegend && m_hasValues && !categories;
    if (!legend && !categories && m_style.caption.empty())
        return;
    const float scale = legendScale(target.width, target.height, m_style.legendScale);
    FontTexture* labels = font(legendLabelPixels(scale));
    FontTexture* title = font(legendTitlePixels(scale));

    // Light panel and dark text on light or transparent backgrounds, the reverse on dark ones.
    const glm::vec4 bg = m_style.background;
    const float luminance = 0.2126f * bg.r + 0.7152f * bg.g + 0.0722f * bg.b;
    const bool dark = !target.transparent && luminance < 0.45f;
    const glm::vec4 panel =
        dark ? glm::vec4(0.08f, 0.09f, 0.11f, 0.72f) : glm::vec4(1.0f, 1.0f, 1.0f, 0.80f);
    const glm::vec4 ink =
        dark ? glm::vec4(0.93f, 0.93f, 0.93f, 1.0f) : glm::vec4(0.10f, 0.10f, 0.12f, 1.0f);

    std::vector<OverlayVertex> solid, bar, labelText, titleText;
    if (categories) {
        const LegendLayout layout = layoutCategoryLegend(
            m_style.categories, m_style.legendTitle, labels ? &labels->atlas : nullptr,
            title ? &title->atlas : nullptr, target.width, target.height, scale);
        m_stats.legendTicks = layout.swatches.size();
        addRect(solid, layout.panel, panel);
        const float o = layout.outline;
        for (std::size_t i = 0; i < layout.swatches.size(); ++i) {
            const LegendRect& r = layout.swatches[i];
            addRect(solid, {r.x0 - o, r.y0 - o, r.x1 + o, r.y1 + o}, ink);
            addRect(solid, r, glm::vec4(layout.swatchColors[i], 1.0f));
        }
        for (const GlyphQuad& g : layout.labelGlyphs)
            addQuad(labelText, g.x0, g.y0, g.x1, g.y1, g.u0, g.v0, g.u1, g.v1, ink);
        for (const GlyphQuad& g : layout.titleGlyphs)
            addQuad(titleText, g.x0, g.y0, g.x1, g.y1, g.u0, g.v0, g.u1, g.v1, ink);
    }
    if (legend) {
        const std::vector<core::LegendTick> ticks =
            core::legendTicks(m_range, 6, m_style.integerValues);
        const LegendLayout layout =
            layoutLegend(ticks, m_style.legendTitle, labels ? &labels->atlas : nullptr,
                         title ? &title->atlas : nullptr, target.width, target.height, scale);
        m_stats.legendTicks = ticks.size();
        addRect(solid, layout.panel, panel);
        const LegendRect& b = layout.bar;
        const float o = layout.outline;
        addRect(solid, {b.x0 - o, b.y0 - o, b.x1 + o, b.y0}, ink);
        addRect(solid, {b.x0 - o, b.y1, b.x1 + o, b.y1 + o}, ink);
        addRect(solid, {b.x0 - o, b.y0, b.x0, b.y1}, ink);
        addRect(solid, {b.x1, b.y0, b.x1 + o, b.y1}, ink);
        for (const LegendRect& t : layout.tickMarks)
            addRect(solid, t, ink);
        // The bar: v is t, 1 at the top.
        addQuad(bar, b.x0, b.y0, b.x1, b.y1, 0, 1, 0, 0, glm::vec4(1.0f));
        for (const GlyphQuad& g : layout.labelGlyphs)
            addQuad(labelText, g.x0, g.y0, g.x1, g.y1, g.u0, g.v0, g.u1, g.v1, ink);
        for (const GlyphQuad& g : layout.titleGlyphs)
            addQuad(titleText, g.x0, g.y0, g.x1, g.y1, g.u0, g.v0, g.u1, g.v1, ink);
    }
    // The caption (a movie frame's timestep) on its own panel in the top-left corner.
    if (!m_style.caption.empty() && title) {
        const FontAtlas& a = title->atlas;
        const float pad = std::round(6.0f * scale);
        const float w = a.measure(m_style.caption);
        addRect(solid, {pad, pad, 3 * pad + w, 3 * pad + a.ascent() + a.descent()}, panel);
        std::vector<GlyphQuad> glyphs;
        a.layout(m_style.caption, 2 * pad, 2 * pad + a.ascent(), glyphs);
        for (const GlyphQuad& g : glyphs)
            addQuad(titleText, g.x0, g.y0, g.x1, g.y1, g.u0, g.v0, g.u1, g.v1, ink);
    }

    if (!m_overlayVao) {
        m_overlayVao = gl::makeVertexArray();
        m_overlayVbo = gl::makeBuffer();
        glBindVertexArray(m_overlayVao.id());
        glBindBuffer(GL_ARRAY_BUFFER, m_overlayVbo.id());
        const GLsizei stride = sizeof(OverlayVertex);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(2 * sizeof(float)));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride,
                              reinterpret_cast<const void*>(4 * sizeof(float)));
    }
    const GLuint p = m_programs.overlay.id();
    glUseProgram(p);
    glUniform2f(gl::uniformLocation(p, "uViewport"), float(target.width), float(target.height));
    glUniform1i(gl::uniformLocation(p, "uFont"), kUnitFont);
    bindColorMap(p, kUnitColorMap);
    glBindVertexArray(m_overlayVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, m_overlayVbo.id());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); // the shader outputs premultiplied colour
    auto draw = [&](const std::vector<OverlayVertex>& v, int mode, FontTexture* tex) {
        if (v.empty())
            return;
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(OverlayVertex)),
                     v.data(), GL_STREAM_DRAW);
        glUniform1i(gl::uniformLocation(p, "uMode"), mode);
        if (tex) {
            glActiveTexture(GL_TEXTURE0 + kUnitFont);
            glBindTexture(GL_TEXTURE_2D, tex->texture.id());
        }
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
    };
    draw(solid, 0, nullptr);
    draw(bar, 2, nullptr);
    draw(labelText, 1, labels);
    draw(titleText, 1, title);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(m_emptyVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

RgbaImage GlRenderer::readImage() {
    RgbaImage img{m_lastTarget.width, m_lastTarget.height, {}};
    if (img.empty() || !m_output.framebuffer())
        return {};
    img.pixels.resize(std::size_t(img.width) * img.height * 4);
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_output.framebuffer());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> raw(img.pixels.size());
    glReadPixels(0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
    const std::size_t rowBytes = std::size_t(img.width) * 4;
    for (int y = 0; y < img.height; ++y) // GL rows go up; images go down
        std::memcpy(&img.pixels[std::size_t(y) * rowBytes],
                    &raw[std::size_t(img.height - 1 - y) * rowBytes], rowBytes);
    if (m_lastTarget.transparent) { // premultiplied -> straight alpha
        for (std::size_t i = 0; i < img.pixels.size(); i += 4) {
            const int a = img.pixels[i + 3];
            if (a == 0 || a == 255)
                continue;
            for (int c = 0; c < 3; ++c)
                img.pixels[i + c] =
                    static_cast<std::uint8_t>(std::min(255, (img.pixels[i + c] * 255 + a / 2) / a));
        }
    }
    return img;
}

} // namespace faultline::ui
