// Milliseconds per frame of the sphere renderer at 1280x720 (impostors with and without occlusion
// culling, and with a transparent surface re-sorted every frame) against drawing every sphere as
// an instanced 320-triangle icosphere, in one run.
// With a display (xvfb-run -a -s "-screen 0 1920x1080x24" ./build/bench/bench_render) it renders
// through GLFW; with DISPLAY unset through EGL, as on a compute node.
#include "core/model/frame.hpp"
#include "core/view/triangle_depth_order.hpp"
#include "ui/render/gl_renderer.hpp"
#include "ui/render/offscreen.hpp"

#include <benchmark/benchmark.h>
#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>

using namespace faultline;

namespace {

constexpr int kWidth = 1280, kHeight = 720;

// A DEM-like block: jittered hexagonal packing nx * ny * nz with a strain band on a dipping plane.
core::Frame makeBlock(int nx, int ny, int nz) {
    core::Frame f;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> jitter(-0.06f, 0.06f), size(0.44f, 0.54f), u(0, 1);
    std::vector<float> strain;
    std::int64_t id = 1;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const float x = float(i) + 0.5f * float(j % 2) + 0.5f * float(k % 2) + jitter(rng);
                const float y = float(j) * 0.866f + 0.29f * float(k % 2) + jitter(rng);
                const float z = float(k) * 0.816f + jitter(rng);
                f.ids.push_back(id++);
                f.x.push_back(x);
                f.y.push_back(y);
                f.z.push_back(z);
                f.radius.push_back(size(rng));
                const float d = (x - 0.45f * nx - (z - 0.4f * nz) * 0.577f) * 0.866f;
                strain.push_back(0.45f * std::exp(-d * d / 2.0f) * (0.7f + 0.3f * u(rng)));
            }
    f.attributes.push_back(core::makeAttribute("strain", std::move(strain), false));
    f.finalize();
    return f;
}

const core::Frame& block(int count) {
    static std::map<int, core::Frame> blocks;
    auto it = blocks.find(count);
    if (it == blocks.end()) {
        // 100,000 = 80 x 50 x 25; 525,000 = 150 x 70 x 50 (the paper's size).
        it = count == 525000 ? blocks.emplace(count, makeBlock(150, 70, 50)).first
                             : blocks.emplace(count, makeBlock(80, 50, count / 4000)).first;
    }
    return it->second;
}

bool haveContext(benchmark::State& state) {
    std::string why;
    if (!ui::sharedOffscreenContext(why)) {
        state.SkipWithError(("no OpenGL context: " + why).c_str());
        return false;
    }
    return true;
}

ui::SceneDescription sceneOf(const core::Frame& f) {
    ui::SceneDescription scene;
    scene.frame = &f;
    scene.colorVariable = "strain";
    scene.colorRange = core::ValueRange{0.0, 0.5};
    return scene;
}

void impostors(benchmark::State& state, ui::OcclusionCulling culling, bool ao) {
    if (!haveContext(state))
        return;
    const core::Frame& f = block(static_cast<int>(state.range(0)));
    ui::SceneDescription scene = sceneOf(f);
    scene.style.culling = culling;
    scene.style.ambientOcclusion = ao;
    ui::GlRenderer renderer;
    ui::loadScene(renderer, scene);
    const core::Camera camera = ui::fittedCamera(scene, kWidth, kHeight);
    const ui::RenderTarget target{kWidth, kHeight, 1, false};
    renderer.render(camera, target); // warm-up: shader compilation, allocation
    glFinish();
    for (auto _ : state) {
        renderer.render(camera, target);
        glFinish();
    }
    const ui::RenderStats& s = renderer.stats();
    state.counters["spheres"] = double(s.visibleSpheres);
    state.counters["drawn"] = double(s.drawnSpheres);
    state.counters["culled"] = double(s.occlusionCulled + s.frustumCulled);
    state.SetLabel(renderer.rendererName());
}

// ---- transparent fault surfaces: triangles sorted back to front when the view moves ----

// A wavy dipping sheet through the block of about `triangles` triangles, half transparent.
ui::MeshData faultSheet(const core::Frame& f, int triangles) {
    const auto [lo, hi] = std::minmax_element(f.x.begin(), f.x.end());
    const float x0 = *lo, x1 = *hi;
    const float y1 = *std::max_element(f.y.begin(), f.y.end());
    const float z1 = *std::max_element(f.z.begin(), f.z.end());
    const int n = std::max(2, int(std::sqrt(triangles / 2.0)));
    ui::MeshData m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float u = float(i) / float(n), v = float(j) / float(n);
            const float x = x0 + (x1 - x0) * (0.3f + 0.4f * v) + 0.8f * std::sin(9.0f * u);
            m.positions.insert(m.positions.end(), {x, u * y1, v * z1});
            m.colors.insert(m.colors.end(), {0.9f, 0.4f + 0.3f * v, 0.2f});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 1,
                       d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, c, b, d});
        }
    m.opacity = 0.5f;
    return m;
}

// CPU cost of re-sorting a surface's triangles after the camera moved.
void transparentSort(benchmark::State& state) {
    const core::Frame& f = block(100000);
    const ui::MeshData sheet = faultSheet(f, int(state.range(0)));
    core::TriangleDepthOrder order;
    order.setTriangles(sheet.positions, sheet.indices);
    glm::dvec3 eye(-40.0, -60.0, 50.0);
    for (auto _ : state) {
        eye.x += 0.01;
        order.update(eye, glm::dvec3(0, 1, 0), true);
        benchmark::DoNotOptimize(order.indices().data());
    }
    state.counters["triangles"] = double(order.triangleCount());
}

// A frame of spheres and a transparent surface while the camera turns (a sort every frame).
void impostorsWithSurface(benchmark::State& state) {
    if (!haveContext(state))
        return;
    const core::Frame& f = block(100000);
    ui::SceneDescription scene = sceneOf(f);
    scene.meshes.push_back(faultSheet(f, int(state.range(0))));
    ui::GlRenderer renderer;
    ui::loadScene(renderer, scene);
    core::Camera camera = ui::fittedCamera(scene, kWidth, kHeight);
    const ui::RenderTarget target{kWidth, kHeight, 1, false};
    renderer.render(camera, target);
    glFinish();
    for (auto _ : state) {
        core::orbitTurntable(camera, 0.002, 0.0);
        renderer.render(camera, target);
        glFinish();
    }
    state.counters["triangles"] = double(renderer.stats().meshTriangles);
    state.counters["sorts"] = double(renderer.stats().meshSorts);
}

// ---- the baseline: an instanced icosphere of 320 triangles per sphere ----

const char* kMeshVertex = R"(#version 410 core
layout(location = 0) in vec3 aPos;       // unit icosphere vertex (= normal)
layout(location = 1) in vec4 aSphere;    // per instance: centre, radius
layout(location = 2) in float aValue;    // per instance
uniform mat4 uView;
uniform mat4 uProj;
out vec3 vNormal;
out float vValue;
void main() {
    vNormal = mat3(uView) * aPos;
    vValue = aValue;
    gl_Position = uProj * uView * vec4(aSphere.xyz + aPos * aSphere.w, 1.0);
}
)";
const char* kMeshFragment = R"(#version 410 core
in vec3 vNormal;
in float vValue;
out vec4 oColor;
void main() {
    vec3 n = normalize(vNormal);
    float t = clamp(vValue / 0.5, 0.0, 1.0);
    vec3 base = mix(vec3(0.05, 0.2, 1.0), vec3(1.0, 0.1, 0.05), t);
    float d = max(dot(n, normalize(vec3(-0.4, 0.6, 0.7))), 0.0);
    oColor = vec4(base * (0.25 + 0.75 * d), 1.0);
}
)";

// Icosahedron subdivided twice: 320 triangles, 162 vertices.
void icosphere(std::vector<glm::vec3>& vertices, std::vector<std::uint32_t>& indices) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (auto& v : vertices)
        v = glm::normalize(v);
    indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int level = 0; level < 2; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end())
                return it->second;
            vertices.push_back(glm::normalize(vertices[a] + vertices[b]));
            const auto idx = static_cast<std::uint32_t>(vertices.size() - 1);
            mid[key] = idx;
            return idx;
        };
        std::vector<std::uint32_t> next;
        for (std::size_t i = 0; i < indices.size(); i += 3) {
            const std::uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        indices = std::move(next);
    }
}

void meshSpheres(benchmark::State& state) {
    if (!haveContext(state))
        return;
    const core::Frame& f = block(static_cast<int>(state.range(0)));
    const ui::SceneDescription scene = sceneOf(f);
    const core::Camera camera = ui::fittedCamera(scene, kWidth, kHeight);

    std::vector<glm::vec3> vertices;
    std::vector<std::uint32_t> indices;
    icosphere(vertices, indices);
    if (indices.size() != 960)
        throw std::logic_error("icosphere must have 320 triangles");
    std::vector<float> instances;
    instances.reserve(f.size() * 5);
    const auto& strain = f.attribute("strain")->floats;
    for (std::size_t i = 0; i < f.size(); ++i)
        instances.insert(instances.end(), {f.x[i], f.y[i], f.z[i], f.radius[i], strain[i]});

    ui::gl::Program program = ui::gl::makeProgram("icosphere", kMeshVertex, kMeshFragment);
    ui::gl::VertexArray vao = ui::gl::makeVertexArray();
    ui::gl::Buffer vbo = ui::gl::makeBuffer(), ibo = ui::gl::makeBuffer(),
                   inst = ui::gl::makeBuffer();
    glBindVertexArray(vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(glm::vec3)), vertices.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, inst.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(float)), instances.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 5 * sizeof(float), nullptr);
    glVertexAttribDivisor(1, 1);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 5 * sizeof(float),
                          reinterpret_cast<const void*>(4 * sizeof(float)));
    glVertexAttribDivisor(2, 1);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(std::uint32_t)),
                 indices.data(), GL_STATIC_DRAW);

    ui::gl::RenderTexture target;
    target.ensure(kWidth, kHeight, true);
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glViewport(0, 0, kWidth, kHeight);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE); // back faces culled, as any mesh renderer would
    glUseProgram(program.id());
    // The same bounds as the renderer's clip planes.
    const core::BoundingSphere bounds = core::boundingSphereOf(f.x, f.y, f.z, f.radius);
    const glm::mat4 view(core::viewMatrix(camera));
    const glm::mat4 proj(core::projectionMatrix(camera, double(kWidth) / kHeight,
                                                core::clipRangeFor(camera, bounds)));
    glUniformMatrix4fv(glGetUniformLocation(program.id(), "uView"), 1, GL_FALSE,
                       glm::value_ptr(view));
    glUniformMatrix4fv(glGetUniformLocation(program.id(), "uProj"), 1, GL_FALSE,
                       glm::value_ptr(proj));
    auto draw = [&] {
        glClearColor(1, 1, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDrawElementsInstanced(GL_TRIANGLES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr,
                                GLsizei(f.size()));
        glFinish();
    };
    draw(); // warm-up
    for (auto _ : state)
        draw();
    glDisable(GL_CULL_FACE);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state.counters["spheres"] = double(f.size());
    state.counters["triangles"] = double(f.size()) * 320.0;
}

} // namespace

BENCHMARK_CAPTURE(impostors, culling_auto, ui::OcclusionCulling::Auto, true)
    ->Arg(100000)
    ->Arg(525000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK_CAPTURE(impostors, culling_off, ui::OcclusionCulling::Off, true)
    ->Arg(100000)
    ->Arg(525000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK_CAPTURE(impostors, culling_auto_no_ao, ui::OcclusionCulling::Auto, false)
    ->Arg(100000)
    ->Arg(525000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK_CAPTURE(impostors, culling_off_no_ao, ui::OcclusionCulling::Off, false)
    ->Arg(100000)
    ->Arg(525000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(transparentSort)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(impostorsWithSurface)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(meshSpheres)
    ->Arg(100000)
    ->Arg(525000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

BENCHMARK_MAIN();
