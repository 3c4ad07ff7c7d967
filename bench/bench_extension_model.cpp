// Speed of the bonded-sphere extension model: sphere-steps per second while faults grow, and the
// cost of writing a frame. Run under the CPU lock: flock /tmp/faultline-cpu.lock
// build/bench/bench_extension_model
#include "core/synth/dump_writer.hpp"
#include "core/synth/extension_model.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>

using namespace faultline::core;

namespace {

// The small model (14,400 spheres), stepped through its extension where bonds break.
void BM_ExtensionSteps(benchmark::State& state) {
    ExtensionModelOptions o = extensionOptionsFor(ModelSize::Small);
    o.threads = static_cast<int>(state.range(0));
    ExtensionModel model(o);
    model.advance(model.frameStep(0) + 600); // settled, extension under way
    const std::int64_t steps = 200;
    for (auto _ : state)
        model.advance(steps);
    state.SetItemsProcessed(state.iterations() * steps *
                            static_cast<std::int64_t>(model.sphereCount()));
    state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations() * steps),
                                                   benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ExtensionSteps)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The 3-D demo block (204,800 spheres) on both cores, stepped where its faults grow: the
// figure beside the small model's (the demo's whole run is timed by faultline generate --demo).
void BM_DemoBlockSteps(benchmark::State& state) {
    ExtensionModel model(extensionDemoOptions());
    model.advance(model.frameStep(0) + 400);
    const std::int64_t steps = 50;
    for (auto _ : state)
        model.advance(steps);
    state.SetItemsProcessed(state.iterations() * steps *
                            static_cast<std::int64_t>(model.sphereCount()));
}
BENCHMARK(BM_DemoBlockSteps)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(4);

// One frame of the demo block (204,800 spheres): strain, snapshot and gzip text (level 1, as
// the demo writes it).
void BM_DemoFrameOutput(benchmark::State& state) {
    ExtensionModel model(extensionDemoOptions());
    const auto path = std::filesystem::temp_directory_path() / "faultline_bench_frame.lammpstrj.gz";
    LammpsDumpWriter writer(path.string(), 1);
    for (auto _ : state)
        writer.write(model.snapshot(), extensionDumpColumns());
    writer.close();
    std::filesystem::remove(path);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(model.sphereCount()));
}
BENCHMARK(BM_DemoFrameOutput)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

BENCHMARK_MAIN();
