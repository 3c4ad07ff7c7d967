// The workbench's cost per UI frame on 525,000 spheres, headless (no GL): idle, while dragging a
// threshold on a histogram (visibility and histograms recomputed every frame), and while
// orbiting a view (only the camera preview changes). "Updates the view within one frame" needs
// the drag frames well under 16 ms; the renderer's own cost comes on top and is benched there.
#include "core/data/dataset.hpp"
#include "core/session/session.hpp"
#include "ui/dock/panel_ids.hpp"
#include "ui/workbench/workbench.hpp"

#include <benchmark/benchmark.h>
#include <imgui.h>

#include <cmath>
#include <memory>

using namespace faultline;

namespace {

constexpr int kNx = 150, kNy = 50, kNz = 70; // 525,000 spheres

core::Frame latticeFrame(std::size_t index) {
    core::Frame f;
    f.timestep = static_cast<std::int64_t>(index) * 1000;
    const std::size_t n = std::size_t(kNx) * kNy * kNz;
    f.ids.resize(n);
    f.x.resize(n), f.y.resize(n), f.z.resize(n), f.radius.assign(n, 0.5f);
    std::vector<float> strain(n);
    std::vector<float> broken(n), layer(n);
    std::size_t row = 0;
    for (int k = 0; k < kNz; ++k)
        for (int j = 0; j < kNy; ++j)
            for (int i = 0; i < kNx; ++i, ++row) {
                f.ids[row] = static_cast<std::int64_t>(row) + 1;
                f.x[row] = static_cast<float>(i), f.y[row] = static_cast<float>(j), f.z[row] = static_cast<float>(k);
                const double fault = std::exp(-std::pow((i - 75 - 0.5 * (k - 35)) / 3.0, 2)); // a dipping band
                strain[row] = static_cast<float>(0.01 * (index + 1) * fault + 0.001 * ((row * 2654435761u) % 1000) / 1000.0);
                broken[row] = std::floor(12 * fault * (index + 1) / 3.0);
                layer[row] = static_cast<float>(k / 7);
            }
    f.attributes.push_back(core::makeAttribute("strain", std::move(strain), false));
    f.attributes.push_back(core::makeAttribute("broken_bonds", std::move(broken), true));
    f.attributes.push_back(core::makeAttribute("layer", std::move(layer), true));
    f.finalize();
    return f;
}

struct Bench {
    core::Session session;
    std::unique_ptr<ui::Workbench> wb;
    ImGuiContext* context = nullptr;
    double time = 1.0;

    Bench() {
        context = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(1920, 1080);
        io.IniFilename = nullptr;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        session.setDataset(core::Dataset::fromLoader(3, latticeFrame));
        wb = std::make_unique<ui::Workbench>(session);
        for (int k = 0; k < 200 && (!wb->mainDisplay() || !wb->mainDisplay()->frame); ++k) {
            wb->frames().waitIdle();
            frame();
        }
        frame();
        frame();
    }
    ~Bench() {
        wb.reset();
        ImGui::DestroyContext(context);
    }
    void frame() {
        ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
        ImGui::NewFrame();
        wb->frame(time);
        ImGui::Render();
        time += 1.0 / 60.0;
    }
    ui::ItemRect rect(const std::string& name) { return wb->items().find(name).value_or(ui::ItemRect{}); }
};

void BM_IdleFrame(benchmark::State& state) {
    Bench b;
    for (auto _ : state)
        b.frame();
    state.counters["spheres"] = static_cast<double>(b.wb->mainDisplay()->frame->size());
}
BENCHMARK(BM_IdleFrame)->Unit(benchmark::kMillisecond);

// Dragging across the strain histogram: a new threshold preview every frame.
void BM_ThresholdDragFrame(benchmark::State& state) {
    Bench b;
    const ui::ItemRect r = b.rect("histogram.strain");
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(r.x0 + (r.x1 - r.x0) * 0.3f, r.cy());
    b.frame();
    io.MouseDown[0] = true;
    b.frame();
    int step = 0;
    std::size_t visible = 0;
    for (auto _ : state) {
        io.MousePos = ImVec2(r.x0 + (r.x1 - r.x0) * (0.5f + 0.002f * static_cast<float>(step++ % 100)), r.cy());
        b.frame();
        visible = b.wb->mainDisplay()->visibility->visibleCount;
    }
    io.MouseDown[0] = false;
    b.frame();
    state.counters["visible"] = static_cast<double>(visible);
}
BENCHMARK(BM_ThresholdDragFrame)->Unit(benchmark::kMillisecond);

// Orbiting the main view: only the camera preview changes.
void BM_OrbitDragFrame(benchmark::State& state) {
    Bench b;
    const ui::ItemRect r = b.rect("view.image.main");
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(r.cx(), r.cy());
    b.frame();
    io.MouseDown[0] = true;
    b.frame();
    int step = 0;
    for (auto _ : state) {
        io.MousePos = ImVec2(r.cx() + static_cast<float>(step++ % 200), r.cy());
        b.frame();
    }
    io.MouseDown[0] = false;
    b.frame();
}
BENCHMARK(BM_OrbitDragFrame)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
