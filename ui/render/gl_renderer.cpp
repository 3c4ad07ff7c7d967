#include "ui/render/gl_renderer.hpp"

#include "ui/render/gl_shaders.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace faultline::ui {

namespace {

// Texture units, fixed per kind.
constexpr GLuint kUnitSpheres = 0, kUnitValues = 1, kUnitRows = 2, kUnitColorMap = 3;

// Culling pays only when many spheres can hide each other.
constexpr std::size_t kMinSpheresToCull = 20000;
constexpr int kMaxOccluderRounds = 3;

bool isSoftware(const std::string& renderer) {
    for (const char* name : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer",
                             "GDI Generic", "lavapipe"}) {
        if (renderer.find(name) != std::string::npos)
            return true;
    }
    return false;
}

using gl::setMat4;

core::BoundingSphere boxSphere(const glm::dvec3& lo, const glm::dvec3& hi) {
    return {(lo + hi) * 0.5, glm::length(hi - lo) * 0.5};
}

// Sampler units by name; each program samples only some of these.
void setSamplers(GLuint program) {
    glUseProgram(program);
    glUniform1i(gl::optionalUniformLocation(program, "uSpheres"), kUnitSpheres);
    glUniform1i(gl::optionalUniformLocation(program, "uValues"), kUnitValues);
    glUniform1i(gl::optionalUniformLocation(program, "uRows"), kUnitRows);
    glUniform1i(gl::optionalUniformLocation(program, "uColorMap"), kUnitColorMap);
    glUniform1i(gl::optionalUniformLocation(program, "uSegments"), kUnitSpheres);
}

} // namespace

GlRenderer::GlRenderer() {
    const GLubyte* version = glGetString(GL_VERSION);
    if (!version)
        throw std::runtime_error("no current OpenGL context");
    if (epoxy_gl_version() < 41)
        throw std::runtime_error(std::string("OpenGL 4.1 or newer is needed; this context is ") +
                                 reinterpret_cast<const char*>(version));
    const GLubyte* renderer = glGetString(GL_RENDERER);
    m_rendererName = renderer ? reinterpret_cast<const char*>(renderer) : "";
    m_software = isSoftware(m_rendererName);

    namespace s = gl::shaders;
    m_programs.spheresPerspective =
        gl::makeProgram("spheres", s::sphereVertex(true), s::sphereFragment(true));
    m_programs.spheresOrthographic =
        gl::makeProgram("spheres (orthographic)", s::sphereVertex(false), s::sphereFragment(false));
    m_programs.points = gl::makeProgram("context points", s::pointVertex(), s::pointFragment());
    m_programs.mesh = gl::makeProgram("mesh", s::meshVertex(), s::meshFragment());
    m_programs.lines = gl::makeProgram("lines", s::lineVertex(), s::lineFragment());
    m_programs.occlusion =
        gl::makeProgram("occlusion", s::fullscreenVertex(), s::ambientOcclusionFragment());
    m_programs.composite =
        gl::makeProgram("composite", s::fullscreenVertex(), s::compositeFragment());
    m_programs.downsample =
        gl::makeProgram("downsample", s::fullscreenVertex(), s::downsampleFragment());
    m_programs.overlay = gl::makeProgram("overlay", s::overlayVertex(), s::overlayFragment());
    for (const gl::Program* p : {&m_programs.spheresPerspective, &m_programs.spheresOrthographic,
                                 &m_programs.points, &m_programs.lines, &m_programs.overlay})
        setSamplers(p->id());
    glUseProgram(0);

    m_emptyVao = gl::makeVertexArray();
    // Empty until set: one far-away sphere of radius 0 keeps the buffer textures valid.
    const float none[4] = {0, 0, 0, 0};
    m_spheresTex.upload(none, sizeof none, GL_RGBA32F);
    m_valuesTex.upload(none, sizeof none, GL_R32F);
    m_visibleTex.upload(nullptr, 0, GL_R32UI);
    m_hiddenTex.upload(nullptr, 0, GL_R32UI);
    m_segmentsTex.upload(nullptr, 0, GL_RGBA32F);
    setColorMap(m_map);
}

GlRenderer::~GlRenderer() = default;

void GlRenderer::setSpheres(const SphereColumns& s) {
    const std::size_t n = s.x.size();
    assert(s.y.size() == n && s.z.size() == n && s.radius.size() == n);
    m_x.assign(s.x.begin(), s.x.end());
    m_y.assign(s.y.begin(), s.y.end());
    m_z.assign(s.z.begin(), s.z.end());
    m_r.assign(s.radius.begin(), s.radius.end());
    if (s.radiusScale != 1.0f)
        for (float& r : m_r)
            r *= s.radiusScale;
    std::vector<float> packed(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
        packed[4 * i + 0] = s.x[i];
        packed[4 * i + 1] = s.y[i];
        packed[4 * i + 2] = s.z[i];
        packed[4 * i + 3] = std::max(0.0f, m_r[i]);
    }
    m_spheresTex.upload(packed.data(), packed.size() * sizeof(float), GL_RGBA32F);
    ++m_stats.positionUploads;
    m_sphereBounds = core::boundingSphereOf(m_x, m_y, m_z, m_r);
    // Median radius of a sample: the scale of creases for the contact darkening.
    std::vector<float> sample;
    const std::size_t step = std::max<std::size_t>(1, n / 4096);
    for (std::size_t i = 0; i < n; i += step)
        sample.push_back(m_r[i]);
    if (!sample.empty()) {
        std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
        m_typicalRadius = std::max(1e-9, double(sample[sample.size() / 2]));
    }
    m_hasValues = false;
    setVisibleMask({});
}

void GlRenderer::setSphereValues(std::span<const float> values) {
    assert(values.empty() || values.size() == m_x.size());
    m_hasValues = !values.empty();
    if (m_hasValues)
        m_valuesTex.upload(values.data(), values.size_bytes(), GL_R32F);
    ++m_stats.valueUploads;
}

void GlRenderer::setVisibleMask(std::span<const std::uint8_t> mask) {
    assert(mask.empty() || mask.size() == m_x.size());
    compactRows(m_x.size(), mask, m_visible, &m_hidden);
    m_visibleTex.upload(m_visible.data(), m_visible.size() * sizeof(std::uint32_t), GL_R32UI);
    m_hiddenTex.upload(m_hidden.data(), m_hidden.size() * sizeof(std::uint32_t), GL_R32UI);
    ++m_stats.visibilityUploads;
}

void GlRenderer::setColorMap(const core::ColorMapSpec& map) {
    m_map = map;
    const core::ColorMapTexture table = core::colorMapTexture(map);
    if (!m_colorMapTex)
        m_colorMapTex = gl::makeTexture();
    glBindTexture(GL_TEXTURE_2D, m_colorMapTex.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, table.width, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 table.rgba.data());
    const GLint filter = table.nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    m_bandCount = table.bandCount;
    ++m_stats.colorMapUploads;
}

void GlRenderer::setColorRange(core::ValueRange range) { m_range = core::widenDegenerate(range); }

void GlRenderer::setBoxes(std::span<const BoxOverlay> boxes,
                          std::optional<BoxHandlesOverlay> selected) {
    m_boxes.assign(boxes.begin(), boxes.end());
    m_selected = selected && selected->box < m_boxes.size() ? selected : std::nullopt;
    uploadSegments();
}

void GlRenderer::setStyle(const RenderStyle& style) { m_style = style; }

core::BoundingSphere GlRenderer::sceneBounds() const {
    core::BoundingSphere b = core::enclose(m_sphereBounds, m_meshBounds);
    for (const BoxOverlay& box : m_boxes)
        b = core::enclose(b, boxSphere(box.lo, box.hi));
    return b;
}

void GlRenderer::uploadSegments() {
    std::vector<float> data;
    m_segmentCount = 0;
    for (std::size_t bi = 0; bi < m_boxes.size(); ++bi) {
        const BoxOverlay& b = m_boxes[bi];
        const bool selected = m_selected && m_selected->box == bi;
        auto corner = [&](int i) {
            return glm::dvec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y,
                              i & 4 ? b.hi.z : b.lo.z);
        };
        for (int i = 0; i < 8; ++i) {
            for (int axis = 0; axis < 3; ++axis) {
                const int j = i | (1 << axis);
                if (j == i)
                    continue;
                const glm::dvec3 a = corner(i), c = corner(j);
                const float alpha = selected ? 1.0f : 0.85f;
                data.insert(data.end(),
                            {float(a.x), float(a.y), float(a.z), 1.0f, float(c.x), float(c.y),
                             float(c.z), 1.0f, b.color.r, b.color.g, b.color.b, alpha});
                ++m_segmentCount;
            }
        }
    }
    m_segmentsTex.upload(data.data(), data.size() * sizeof(float), GL_RGBA32F);

    // Handle spheres of the selected box, in BoxFace order.
    if (m_selected) {
        const BoxOverlay& b = m_boxes[m_selected->box];
        const double radius = m_selected->handleRadius > 0.0
                                  ? m_selected->handleRadius
                                  : core::defaultHandleRadius(b.lo, b.hi);
        std::vector<float> spheres;
        std::vector<std::uint32_t> rows;
        for (const core::BoxHandle& h : core::boxFaceHandles(b.lo, b.hi)) {
            const bool active = m_selected->activeFace == h.face;
            spheres.insert(spheres.end(), {float(h.centre.x), float(h.centre.y), float(h.centre.z),
                                           float(radius * (active ? 1.3 : 1.0))});
            rows.push_back(static_cast<std::uint32_t>(rows.size()));
        }
        m_handleSpheresTex.upload(spheres.data(), spheres.size() * sizeof(float), GL_RGBA32F);
        m_handleRowsTex.upload(rows.data(), rows.size() * sizeof(std::uint32_t), GL_R32UI);
    }
}

void GlRenderer::bindColorMap(GLuint program, GLuint unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, m_colorMapTex.id());
    glUniform1i(gl::uniformLocation(program, "uBandCount"), m_bandCount);
}

void GlRenderer::useSphereProgram(const FrameSetup& f) {
    const GLuint p =
        f.perspective ? m_programs.spheresPerspective.id() : m_programs.spheresOrthographic.id();
    glUseProgram(p);
    setMat4(p, "uView", f.view);
    setMat4(p, "uProj", f.projection);
    glUniform1f(gl::uniformLocation(p, "uNearZ"), float(-f.clip.nearClip));
    glUniform1i(gl::uniformLocation(p, "uColorMode"), m_hasValues ? 1 : 0);
    glUniform3fv(gl::uniformLocation(p, "uColor"), 1, glm::value_ptr(m_style.sphereColor));
    const glm::vec3 nan = core::nanColor(m_map);
    glUniform3fv(gl::uniformLocation(p, "uNanColor"), 1, glm::value_ptr(nan));
    glUniform2f(gl::uniformLocation(p, "uRange"), float(m_range.low),
                float(1.0 / (m_range.high - m_range.low)));
    glUniform1f(gl::uniformLocation(p, "uSpecular"), m_style.specular);
    m_spheresTex.bind(kUnitSpheres);
    m_valuesTex.bind(kUnitValues);
    bindColorMap(p, kUnitColorMap);
}

void GlRenderer::drawSphereRows(const gl::BufferTexture& rows, std::size_t count) {
    if (count == 0)
        return;
    rows.bind(kUnitRows);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(3 * count));
    m_stats.drawnSpheres += count;
}

void GlRenderer::drawSpheres(const FrameSetup& f) {
    m_stats.drawnSpheres = 0;
    m_stats.occluderPasses = m_stats.frustumCulled = m_stats.occlusionCulled = 0;
    if (m_visible.empty())
        return;
    useSphereProgram(f);
    const bool cull = m_visible.size() >= kMinSpheresToCull &&
                      (m_style.culling == OcclusionCulling::On ||
                       (m_style.culling == OcclusionCulling::Auto && m_software));
    if (!cull) {
        drawSphereRows(m_visibleTex, m_visible.size());
        return;
    }
    // Draw the nearest sphere of each small screen tile, read the depth back, drop every sphere
    // wholly behind it; repeat a few rounds (pores let deeper spheres show), then draw the rest.
    core::SphereProjection projection{f.view, f.projection, f.width, f.height, f.perspective};
    m_culler.begin(m_x, m_y, m_z, m_r, m_visible, projection);
    m_depth.resize(std::size_t(f.width) * f.height);
    for (int round = 0; round < kMaxOccluderRounds && m_culler.candidateCount() > 0; ++round) {
        const std::vector<std::uint32_t> occluders = m_culler.takeOccluders(0);
        if (occluders.empty())
            break;
        m_passRowsTex.upload(occluders.data(), occluders.size() * sizeof(std::uint32_t), GL_R32UI);
        drawSphereRows(m_passRowsTex, occluders.size());
        ++m_stats.occluderPasses;
        if (m_culler.candidateCount() == 0)
            break;
        glReadPixels(0, 0, f.width, f.height, GL_DEPTH_COMPONENT, GL_FLOAT, m_depth.data());
        m_culler.cullBehind(m_depth);
        if (m_culler.candidateCount() < occluders.size() / 8)
            break; // few left: drawing them costs less than another read-back
    }
    const std::vector<std::uint32_t> rest = m_culler.takeRemaining();
    m_passRowsTex.upload(rest.data(), rest.size() * sizeof(std::uint32_t), GL_R32UI);
    drawSphereRows(m_passRowsTex, rest.size());
    m_stats.frustumCulled = m_culler.frustumCulled();
    m_stats.occlusionCulled = m_culler.occlusionCulled();
}

void GlRenderer::drawContextPoints(const FrameSetup& f) {
    m_stats.contextPoints = 0;
    if (!m_style.contextPoints || m_hidden.empty())
        return;
    // Into a layer of its own, depth-tested against the spheres but not blended: each pixel
    // holds at most one point, so hundreds of thousands of them make an even ghost of the
    // hidden material (the composite lays it over the scene) rather than a dark moire mass.
    m_contextLayer.ensureSharingDepth(f.width, f.height, m_scene.depth());
    glBindFramebuffer(GL_FRAMEBUFFER, m_contextLayer.framebuffer());
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    const GLuint p = m_programs.points.id();
    glUseProgram(p);
    setMat4(p, "uView", f.view);
    setMat4(p, "uProj", f.projection);
    glUniform1f(gl::uniformLocation(p, "uPointSize"),
                std::max(1.0f, m_style.contextPointSize * float(f.supersample)));
    const glm::vec4 color(glm::vec3(m_style.contextColor), 1.0f);
    glUniform4fv(gl::uniformLocation(p, "uColor"), 1, glm::value_ptr(color));
    m_spheresTex.bind(kUnitSpheres);
    m_hiddenTex.bind(kUnitRows);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDepthMask(GL_FALSE);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(m_hidden.size()));
    glDepthMask(GL_TRUE);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindFramebuffer(GL_FRAMEBUFFER, m_scene.framebuffer());
    m_stats.contextPoints = m_hidden.size();
}

void GlRenderer::drawBoxEdges(const FrameSetup& f, float widthPx, float alpha, bool depthTest) {
    if (m_segmentCount == 0)
        return;
    const GLuint p = m_programs.lines.id();
    glUseProgram(p);
    setMat4(p, "uView", f.view);
    setMat4(p, "uProj", f.projection);
    glUniform2f(gl::uniformLocation(p, "uViewport"), float(f.width), float(f.height));
    glUniform1f(gl::uniformLocation(p, "uWidth"), widthPx);
    glUniform1f(gl::uniformLocation(p, "uNearZ"),
                f.perspective ? float(-f.clip.nearClip * 1.0001) : 1.0f);
    glUniform1f(gl::uniformLocation(p, "uAlpha"), alpha);
    m_segmentsTex.bind(kUnitSpheres);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    if (!depthTest)
        glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6 * m_segmentCount));
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void GlRenderer::render(const core::Camera& camera, const RenderTarget& target) {
    if (target.width <= 0 || target.height <= 0)
        throw std::invalid_argument("render target must be at least 1x1");
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    int s = std::clamp(target.supersample, 1, 4);
    while (s > 1 && std::max(target.width, target.height) * s > maxSize)
        --s;
    if (std::max(target.width, target.height) > maxSize ||
        std::max(target.width, target.height) * s > 65535)
        throw std::invalid_argument("render target larger than this OpenGL allows (" +
                                    std::to_string(maxSize) + " pixels)");
    // Keep the caller's framebuffer, viewport and scissor (ImGui draws after us).
    GLint previousFbo = 0, previousViewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_VIEWPORT, previousViewport);
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    const GLboolean cullFace = glIsEnabled(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    m_lastTarget = target;
    m_lastTarget.supersample = s;
    FrameSetup f;
    f.width = target.width * s;
    f.height = target.height * s;
    f.supersample = s;
    f.perspective = camera.projection == core::Projection::Perspective;
    f.eye = camera.eye();
    f.forward = camera.forward();
    const double aspect = double(target.width) / double(target.height);
    f.clip = core::clipRangeFor(camera, sceneBounds());
    f.view = core::viewMatrix(camera);
    f.projection = core::projectionMatrix(camera, aspect, f.clip);

    m_scene.ensure(f.width, f.height, true);
    m_output.ensure(target.width, target.height, true);
    if (s > 1)
        m_composite.ensure(f.width, f.height, false);
    if (m_style.ambientOcclusion)
        m_occlusion.ensure((f.width + 1) / 2, (f.height + 1) / 2, false);

    m_stats.spheres = m_x.size();
    m_stats.visibleSpheres = m_visible.size();
    m_stats.meshTriangles = 0;
    m_stats.boxes = m_boxes.size();

    // Scene at the supersampled size.
    glBindFramebuffer(GL_FRAMEBUFFER, m_scene.framebuffer());
    glViewport(0, 0, f.width, f.height);
    const glm::vec4 bg = target.transparent ? glm::vec4(0.0f) : m_style.background;
    glClearColor(bg.r * bg.a, bg.g * bg.a, bg.b * bg.a, bg.a); // premultiplied
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(m_emptyVao.id());

    // Opaque first; transparent surfaces last, blended back to front over everything.
    gl::checkErrors("render setup");
    drawSpheres(f);
    gl::checkErrors("spheres");
    drawOpaqueMeshes(f);
    gl::checkErrors("opaque meshes");
    drawContextPoints(f);
    gl::checkErrors("context points");
    drawBoxEdges(f, m_style.lineWidth * float(s), 1.0f, true);
    gl::checkErrors("box edges");
    drawTransparentMeshes(f);
    gl::checkErrors("transparent meshes");

    composite(f, target);
    gl::checkErrors("composite");

    // Overlays at the output size: hidden box edges faintly, handles, legend.
    FrameSetup o = f;
    o.width = target.width;
    o.height = target.height;
    o.supersample = 1;
    glBindFramebuffer(GL_FRAMEBUFFER, m_output.framebuffer());
    glViewport(0, 0, o.width, o.height);
    glClear(GL_DEPTH_BUFFER_BIT);
    drawBoxEdges(o, std::max(1.0f, m_style.lineWidth * 0.6f), 0.3f, false);
    drawHandles(o);
    gl::checkErrors("overlays");
    drawLegend(target);
    gl::checkErrors("legend");

    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previousFbo));
    glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
    if (cullFace)
        glEnable(GL_CULL_FACE);
}

} // namespace faultline::ui
