// Session speed: applying 10,000 recorded commands, and saving / loading a session with 50
// faults of 100,000 member ids each (issue: each under 1 s).
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

using namespace faultline::core;

namespace {

std::vector<Json> recordedCommands(std::size_t n) {
    std::vector<Json> cmds;
    std::mt19937 rng(1);
    for (std::size_t k = 0; cmds.size() < n; ++k) {
        const std::string box = "b" + std::to_string(k);
        cmds.push_back({{"op", "box.add"}, {"name", box}, {"min", {0, 0, 0}}, {"max", {1, 2, 3}}});
        cmds.push_back({{"op", "box.set"}, {"name", box}, {"max", {2, 2, 2}}, {"mode", "cut"}});
        cmds.push_back({{"op", "threshold.add"},
                        {"variable", "v" + std::to_string(k)},
                        {"low", 0},
                        {"high", 1}});
        cmds.push_back(
            {{"op", "threshold.set"}, {"variable", "v" + std::to_string(k)}, {"low", 0.5}});
        std::vector<std::int64_t> ids(20);
        for (auto& id : ids)
            id = static_cast<std::int64_t>(rng() % 100000);
        cmds.push_back({{"op", "fault.create"}, {"name", "F" + std::to_string(k)}, {"ids", ids}});
        cmds.push_back({{"op", "fault.set"}, {"name", "F" + std::to_string(k)}, {"notes", "n"}});
        cmds.push_back({{"op", "undo"}});
        cmds.push_back({{"op", "redo"}});
        cmds.push_back({{"op", "box.remove"}, {"name", box}});
        cmds.push_back({{"op", "camera.set"}, {"azimuth", static_cast<double>(k % 360)}});
    }
    cmds.resize(n);
    return cmds;
}

void BM_Apply10000Commands(benchmark::State& state) {
    const auto cmds = recordedCommands(10000);
    for (auto _ : state) {
        Session s;
        for (const auto& c : cmds)
            s.apply(c);
        benchmark::DoNotOptimize(s.version());
    }
}

SessionState bigSession() {
    SessionState st;
    std::mt19937_64 rng(7);
    for (int f = 0; f < 50; ++f) {
        Fault fault;
        fault.name = "F" + std::to_string(f);
        fault.ids.resize(100000);
        for (auto& id : fault.ids)
            id = static_cast<std::int64_t>(rng() % 5000000);
        normalizeIds(fault.ids);
        st.faults.push_back(std::move(fault));
    }
    return st;
}

const std::string& sessionPath() {
    static const std::string p =
        (std::filesystem::temp_directory_path() / "faultline-bench.faultline.json").string();
    return p;
}

void BM_Save50FaultsOf100kIds(benchmark::State& state) {
    const SessionState st = bigSession();
    for (auto _ : state)
        saveSessionFile(st, sessionPath());
    state.counters["MB"] = static_cast<double>(std::filesystem::file_size(sessionPath())) / 1e6;
}

void BM_Load50FaultsOf100kIds(benchmark::State& state) {
    saveSessionFile(bigSession(), sessionPath());
    for (auto _ : state) {
        SessionState st = loadSessionFile(sessionPath());
        benchmark::DoNotOptimize(st.faults.size());
    }
}

} // namespace

BENCHMARK(BM_Apply10000Commands)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Save50FaultsOf100kIds)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Load50FaultsOf100kIds)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
