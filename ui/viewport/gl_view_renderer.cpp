#include "ui/viewport/gl_view_renderer.hpp"
#include "ui/render/legend_layout.hpp"

#include "core/color/colormap.hpp"
#include "core/model/packing.hpp"
#include "core/view/box_handles.hpp"
#include "ui/viewport/orbit_camera.hpp"

#include <epoxy/gl.h>

#include <cstdio>
#include <sstream>

namespace faultline::ui {

core::Camera toRenderCamera(const core::CameraState& c) {
    core::Camera cam;
    cam.target = glm::dvec3(c.target[0], c.target[1], c.target[2]);
    cam.distance = std::max(c.distance, 1e-9);
    const CameraBasis b = cameraBasis(c);
    cam.orientation = core::lookRotation(b.forward, glm::dvec3(0, 0, 1));
    cam.fovYDegrees = c.fovY;
    cam.projection =
        c.orthographic ? core::Projection::Orthographic : core::Projection::Perspective;
    return cam;
}

GlViewRenderer::GlViewRenderer(RendererBackend backend) : m_backend(backend) {
    if (backend == RendererBackend::OpenGL) {
        const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        m_description =
            std::string("OpenGL ") + (version ? version : "?") + " on " + (name ? name : "?");
        createRenderer(backend); // fails here, with the reason, when the context cannot do it
    } else {
        m_description = "mock renderer";
    }
}

GlViewRenderer::~GlViewRenderer() = default;

Renderer* GlViewRenderer::rendererOf(const std::string& view) const {
    auto it = m_slots.find(view);
    return it == m_slots.end() ? nullptr : it->second.renderer.get();
}

unsigned int GlViewRenderer::texture(const std::string& view) const {
    auto it = m_slots.find(view);
    return it == m_slots.end() || !it->second.renderer ? 0 : it->second.renderer->colorTexture();
}

void GlViewRenderer::forget(const std::string& view) { m_slots.erase(view); }

void GlViewRenderer::render(const ViewScene& scene) {
    Slot& slot = m_slots[scene.view];
    if (!slot.renderer)
        slot.renderer = createRenderer(m_backend);
    Renderer& r = *slot.renderer;
    bool changed = false;
    if (scene.frame != slot.frame) {
        slot.frame = scene.frame;
        if (scene.frame) {
            const core::Frame& f = *scene.frame;
            r.setSpheres({f.x, f.y, f.z, f.radius, float(core::radiusDrawScale(f))});
        } else {
            r.setSpheres({});
        }
        slot.variable = "\x01";
        slot.visibleKey = ~0ull;
        changed = true;
    }
    if (scene.colorVariable != slot.variable || scene.colorColumn != slot.column) {
        slot.variable = scene.colorVariable;
        slot.column = scene.colorColumn;
        slot.values.clear();
        std::span<const float> values;
        if (scene.frame && !scene.colorVariable.empty()) {
            const core::Frame& f = *scene.frame;
            const core::AttributeColumn* c =
                scene.colorColumn ? scene.colorColumn.get() : f.attribute(scene.colorVariable);
            if (c && c->size() != f.size()) {
                c = nullptr; // a column of another frame: one colour until the right one comes
            } else if (c) {
                if (c->isInteger()) {
                    slot.values.assign(c->ints.begin(), c->ints.end());
                    values = slot.values;
                } else {
                    values = c->floats;
                }
            } else if (scene.colorVariable == "x") {
                values = f.x;
            } else if (scene.colorVariable == "y") {
                values = f.y;
            } else if (scene.colorVariable == "z") {
                values = f.z;
            } else if (scene.colorVariable == "radius") {
                values = f.radius;
            }
        }
        r.setSphereValues(values);
        changed = true;
    }
    // Surfaces: re-sent when a mesh or an opacity changes (meshes are shared, never edited).
    std::vector<std::pair<std::shared_ptr<const MeshData>, float>> surfaceKey;
    for (const auto& sf : scene.surfaces)
        if (sf.mesh)
            surfaceKey.push_back({sf.mesh, sf.opacity});
    if (surfaceKey != slot.surfaceKey) {
        slot.surfaceKey = surfaceKey;
        std::vector<MeshData> meshes;
        meshes.reserve(scene.surfaces.size());
        for (const auto& sf : scene.surfaces)
            if (sf.mesh) {
                meshes.push_back(*sf.mesh);
                meshes.back().opacity = sf.opacity;
            }
        r.setMeshes(meshes);
        changed = true;
    }
    if (scene.visibleKey != slot.visibleKey) {
        slot.visibleKey = scene.visibleKey;
        r.setVisibleMask(scene.visible ? std::span<const std::uint8_t>(*scene.visible)
                                       : std::span<const std::uint8_t>());
        changed = true;
    }
    // The rest is cheap to set; compare it as text to know whether to draw again.
    std::ostringstream sig;
    sig.precision(17);
    sig << core::colorMapName(scene.colorMap) << '|' << scene.colorRange[0] << '|'
        << scene.colorRange[1] << '|' << scene.width << 'x' << scene.height << '|'
        << scene.camera.target[0] << ',' << scene.camera.target[1] << ',' << scene.camera.target[2]
        << '|' << scene.camera.distance << '|' << scene.camera.azimuth << '|'
        << scene.camera.elevation << '|' << scene.camera.fovY << '|' << scene.camera.orthographic
        << '|' << (scene.selectedBox ? int(*scene.selectedBox) : -1) << '|'
        << (scene.activeFace ? *scene.activeFace : -1) << '|' << scene.contextPoints << '|'
        << scene.valueLegend;
    for (const auto& c : scene.palette)
        sig << '|' << c.r << ',' << c.g << ',' << c.b;
    for (const auto& e : scene.legend)
        sig << '|' << e.name;
    for (const auto& b : scene.boxes)
        sig << '|' << b.min[0] << ',' << b.min[1] << ',' << b.min[2] << ',' << b.max[0] << ','
            << b.max[1] << ',' << b.max[2] << ',' << int(b.mode) << ',' << b.enabled;
    if (sig.str() != slot.signature || changed) {
        slot.signature = sig.str();
        auto map = scene.colorMap;
        if (!scene.palette.empty())
            map = core::ColorMapSpec{core::ColorMapKind::Palette, 10, scene.palette};
        r.setColorMap(map);
        r.setColorRange({scene.colorRange[0], scene.colorRange[1]});
        std::vector<BoxOverlay> boxes;
        for (const auto& b : scene.boxes) {
            BoxOverlay o;
            o.lo = glm::dvec3(b.min[0], b.min[1], b.min[2]);
            o.hi = glm::dvec3(b.max[0], b.max[1], b.max[2]);
            o.color = b.mode == core::BoxMode::Keep ? glm::vec3(0.16f, 0.55f, 0.27f)
                                                    : glm::vec3(0.78f, 0.27f, 0.16f);
            boxes.push_back(o);
        }
        std::optional<BoxHandlesOverlay> handles;
        if (scene.selectedBox && *scene.selectedBox < boxes.size()) {
            BoxHandlesOverlay h;
            h.box = *scene.selectedBox;
            const auto& b = scene.boxes[*scene.selectedBox];
            h.handleRadius = core::screenHandleRadius(glm::dvec3(b.min[0], b.min[1], b.min[2]),
                                                      glm::dvec3(b.max[0], b.max[1], b.max[2]),
                                                      scene.camera.distance, scene.camera.fovY);
            if (scene.activeFace)
                h.activeFace = static_cast<core::BoxFace>(*scene.activeFace);
            handles = h;
        }
        r.setBoxes(boxes, handles);
        RenderStyle style;
        style.legendTitle = scene.colorVariable;
        style.showLegend = roomForLegend(scene.width, scene.height) &&
                           !scene.colorVariable.empty() && scene.valueLegend &&
                           (scene.palette.empty() || !scene.legend.empty());
        if (!scene.palette.empty())
            style.categories = scene.legend;
        style.contextPoints = scene.contextPoints;
        r.setStyle(style);
        r.render(toRenderCamera(scene.camera), RenderTarget{scene.width, scene.height, 1, false});
        ++m_draws;
    }
}

} // namespace faultline::ui
