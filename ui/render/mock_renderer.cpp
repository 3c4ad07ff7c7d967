#include "ui/render/mock_renderer.hpp"

#include "core/color/legend_ticks.hpp"

#include <glm/geometric.hpp>

#include <cassert>

namespace faultline::ui {

void MockRenderer::setSpheres(const SphereColumns& s) {
    assert(s.x.size() == s.y.size() && s.x.size() == s.z.size() && s.x.size() == s.radius.size());
    m_x.assign(s.x.begin(), s.x.end());
    m_y.assign(s.y.begin(), s.y.end());
    m_z.assign(s.z.begin(), s.z.end());
    m_r.assign(s.radius.begin(), s.radius.end());
    if (s.radiusScale != 1.0f)
        for (float& r : m_r)
            r *= s.radiusScale;
    m_hasValues = false;
    compactRows(m_x.size(), {}, m_visible, &m_hidden);
    ++m_stats.positionUploads;
    ++m_stats.visibilityUploads;
    record("upload.positions", m_x.size());
    record("upload.visible_rows", m_visible.size());
}

void MockRenderer::setSphereValues(std::span<const float> values) {
    assert(values.empty() || values.size() == m_x.size());
    m_hasValues = !values.empty();
    ++m_stats.valueUploads;
    record("upload.values", values.size());
}

void MockRenderer::setVisibleMask(std::span<const std::uint8_t> mask) {
    assert(mask.empty() || mask.size() == m_x.size());
    compactRows(m_x.size(), mask, m_visible, &m_hidden);
    ++m_stats.visibilityUploads;
    record("upload.visible_rows", m_visible.size());
}

void MockRenderer::setColorMap(const core::ColorMapSpec& map) {
    m_map = map;
    ++m_stats.colorMapUploads;
    record("upload.colormap", static_cast<std::size_t>(core::colorMapTexture(map).width));
}

void MockRenderer::setColorRange(core::ValueRange range) {
    m_range = core::widenDegenerate(range);
    record("uniform.range", 2);
}

void MockRenderer::setMeshes(std::span<const MeshData> meshes) {
    m_meshTriangles = 0;
    m_meshCount = meshes.size();
    m_meshBounds = {};
    for (const MeshData& m : meshes) {
        assert(m.positions.size() % 3 == 0 && m.indices.size() % 3 == 0);
        m_meshTriangles += m.indices.size() / 3;
        const std::size_t n = m.positions.size() / 3;
        if (n == 0)
            continue;
        glm::dvec3 lo(m.positions[0], m.positions[1], m.positions[2]), hi = lo;
        for (std::size_t v = 0; v < n; ++v) {
            const glm::dvec3 p(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        m_meshBounds = core::enclose(m_meshBounds, {(lo + hi) * 0.5, glm::length(hi - lo) * 0.5});
    }
    ++m_stats.meshUploads;
    record("upload.meshes", m_meshTriangles);
}

void MockRenderer::setBoxes(std::span<const BoxOverlay> boxes,
                            std::optional<BoxHandlesOverlay> selected) {
    m_boxes.assign(boxes.begin(), boxes.end());
    m_selected = selected && selected->box < m_boxes.size() ? selected : std::nullopt;
    record("upload.boxes", m_boxes.size());
}

void MockRenderer::setStyle(const RenderStyle& style) { m_style = style; }

void MockRenderer::render(const core::Camera& camera, const RenderTarget& target) {
    (void)camera;
    assert(target.width > 0 && target.height > 0);
    m_lastTarget = target;
    m_frameStart = m_calls.size();
    m_stats.spheres = m_x.size();
    m_stats.visibleSpheres = m_visible.size();
    m_stats.drawnSpheres = m_visible.size(); // the mock never culls
    m_stats.occluderPasses = m_stats.frustumCulled = m_stats.occlusionCulled = 0;
    m_stats.contextPoints = m_style.contextPoints ? m_hidden.size() : 0;
    m_stats.meshTriangles = m_meshTriangles;
    m_stats.boxes = m_boxes.size();
    m_stats.handles = m_selected ? 6 : 0;
    const bool categories = m_style.showLegend && !m_style.categories.empty();
    const bool legend = categories || (m_style.showLegend && m_hasValues);
    m_stats.legendTicks = categories ? m_style.categories.size()
                          : legend   ? core::legendTicks(m_range, 6, m_style.integerValues).size()
                                     : 0;

    record("clear", target.transparent ? 0 : 1);
    if (!m_visible.empty())
        record("draw.spheres", m_visible.size());
    if (m_stats.contextPoints)
        record("draw.context_points", m_stats.contextPoints);
    if (m_meshCount)
        record("draw.meshes", m_meshTriangles);
    if (!m_boxes.empty())
        record("draw.box_edges", m_boxes.size() * 12);
    if (m_style.ambientOcclusion)
        record("post.ambient_occlusion", 1);
    if (target.supersample > 1)
        record("post.downsample", static_cast<std::size_t>(target.supersample));
    if (m_selected)
        record("draw.handles", 6);
    if (legend)
        record("draw.legend", m_stats.legendTicks);
}

std::vector<MockCall> MockRenderer::lastFrame() const {
    return {m_calls.begin() + static_cast<std::ptrdiff_t>(m_frameStart), m_calls.end()};
}

RgbaImage MockRenderer::readImage() {
    // A flat image of the background: the mock draws nothing.
    RgbaImage img{m_lastTarget.width, m_lastTarget.height, {}};
    const glm::vec4 bg = m_lastTarget.transparent ? glm::vec4(0.0f) : m_style.background;
    img.pixels.resize(std::size_t(img.width) * img.height * 4);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4)
        for (int c = 0; c < 4; ++c)
            img.pixels[i + c] = static_cast<std::uint8_t>(bg[c] * 255.0f + 0.5f);
    return img;
}

core::BoundingSphere MockRenderer::sceneBounds() const {
    core::BoundingSphere b = core::boundingSphereOf(m_x, m_y, m_z, m_r);
    b = core::enclose(b, m_meshBounds);
    for (const BoxOverlay& box : m_boxes)
        b = core::enclose(b, {(box.lo + box.hi) * 0.5, glm::length(box.hi - box.lo) * 0.5});
    return b;
}

} // namespace faultline::ui
