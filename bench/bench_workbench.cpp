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

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <thread>

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
                f.x[row] = static_cast<float>(i), f.y[row] = static_cast<float>(j),
                f.z[row] = static_cast<float>(k);
                const double fault =
                    std::exp(-std::pow((i - 75 - 0.5 * (k - 35)) / 3.0, 2)); // a dipping band
                strain[row] = static_cast<float>(0.01 * (index + 1) * fault +
                                                 0.001 * ((row * 2654435761u) % 1000) / 1000.0);
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
    // UI frames (5 ms apart, as background jobs run) until `done`; the seconds it took.
    template <typename Done> double framesUntil(Done done) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int k = 0; k < 100000 && !done(); ++k) {
            frame();
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    ui::ItemRect rect(const std::string& name) {
        return wb->items().find(name).value_or(ui::ItemRect{});
    }
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
        io.MousePos = ImVec2(
            r.x0 + (r.x1 - r.x0) * (0.5f + 0.002f * static_cast<float>(step++ % 100)), r.cy());
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

// Issue 41: "Follow through time" on the demo (204,800 spheres, 40 frames, broken_bonds >= 1,
// the last frame's candidates as faults), as a user runs it from the Faults panel: the first
// time, then again after the faults shown changed (each frame's candidates are kept, so only
// the matching and the metrics run again). Needs the demo: faultline generate --demo.
void BM_FollowThroughTimeDemo(benchmark::State& state) {
    const char* home = std::getenv("HOME");
    const std::string demo =
        std::string(home ? home : "") + "/.local/share/faultline/demo/block-v2.lammpstrj.gz";
    if (!std::filesystem::exists(demo)) {
        state.SkipWithError("no demo: run faultline generate --demo");
        return;
    }
    Bench b;
    b.session.apply({{"op", "data.open"}, {"paths", {demo}}});
    b.session.apply({{"op", "frame.set"}, {"frame", 39}});
    b.session.apply(
        {{"op", "threshold.add"}, {"variable", "broken_bonds"}, {"low", 1}, {"high", 1e30}});
    b.session.apply({{"op", "fault.candidates"}, {"min_size", 200}, {"prefix", "C"}});
    std::set<std::string> all;
    for (const auto& f : b.session.state().faults)
        all.insert(f.name);
    b.wb->selection().faults = all;
    b.wb->layout().setActive(ui::panel_ids::kFaults);
    for (int k = 0; k < 4; ++k)
        b.frame();
    auto waitShown = [&] {
        return b.framesUntil([&] {
            return b.wb->items().find("faults.metrics.events.shown") && !b.wb->jobs().busy();
        });
    };
    double first = 0, again = 0;
    for (auto _ : state) {
        // Metrics of the fixed members first, so they do not count below.
        b.framesUntil([&] { return !b.wb->jobs().busy(); });
        const ui::ItemRect r = b.rect("faults.metrics.events");
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = ImVec2(r.cx(), r.cy());
        b.frame();
        io.MouseDown[0] = true;
        b.frame();
        io.MouseDown[0] = false;
        first = waitShown();
        std::set<std::string> some(all.begin(),
                                   std::next(all.begin(), std::ptrdiff_t(all.size() / 2)));
        b.wb->selection().faults = some;
        b.frame();
        b.frame();
        again = waitShown();
    }
    state.counters["faults"] = static_cast<double>(all.size());
    state.counters["first_s"] = first;
    state.counters["again_s"] = again;
}
BENCHMARK(BM_FollowThroughTimeDemo)->Unit(benchmark::kSecond)->Iterations(1);

} // namespace

BENCHMARK_MAIN();
