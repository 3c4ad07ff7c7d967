// Reader speed: the LAMMPS dump parser on a 525,000-sphere x 9-column dump (~26 MB), beside a
// naive ifstream >> double reader and a plain read of the file, all measured in one run.
#include "core/io/byte_source.hpp"
#include "core/io/lammps_dump.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace faultline::core;

namespace {

constexpr std::size_t kSpheres = 525000;

std::string writeDump(const std::string& name, int frames) {
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    if (std::filesystem::exists(path))
        return path;
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int t = 0; t < frames; ++t) {
        std::fprintf(
            f,
            "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS pp pp ff\n"
            "0 200\n0 40\n0 80\nITEM: ATOMS id type x y z radius strain broken_bonds layer\n",
            t * 1000, kSpheres);
        for (std::size_t i = 0; i < kSpheres; ++i)
            std::fprintf(f, "%zu 1 %.5f %.5f %.5f 0.5 %.5g %d %d\n", i + 1, 200 * u(rng),
                         40 * u(rng), 80 * u(rng), 0.3 * u(rng), static_cast<int>(12 * u(rng)),
                         static_cast<int>(8 * u(rng)));
    }
    std::fclose(f);
    return path;
}

const std::string& singleFrameDump() {
    static const std::string path = writeDump("faultline-bench-525k.lammpstrj", 1);
    return path;
}

void BM_ReadFileOnly(benchmark::State& state) {
    const std::string& path = singleFrameDump();
    for (auto _ : state) {
        std::string bytes = readFileBytes(path);
        benchmark::DoNotOptimize(bytes.data());
    }
    state.SetBytesProcessed(state.iterations() *
                            static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

void BM_FaultlineLammpsParse(benchmark::State& state) {
    const std::string& path = singleFrameDump();
    for (auto _ : state) {
        const std::string bytes = readFileBytes(path);
        Frame frame = parseLammpsDumpFrame(path, bytes);
        benchmark::DoNotOptimize(frame.x.data());
        if (frame.size() != kSpheres)
            state.SkipWithError("wrong sphere count");
    }
    state.SetBytesProcessed(state.iterations() *
                            static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

// The reader a first version would write: getline for the header, >> for every value.
void BM_NaiveIfstreamParse(benchmark::State& state) {
    const std::string& path = singleFrameDump();
    for (auto _ : state) {
        std::ifstream in(path);
        std::string line;
        for (int k = 0; k < 9; ++k)
            std::getline(in, line);
        std::vector<double> columns[9];
        for (auto& c : columns)
            c.reserve(kSpheres);
        double v;
        for (std::size_t i = 0; i < kSpheres; ++i)
            for (auto& c : columns) {
                in >> v;
                c.push_back(v);
            }
        benchmark::DoNotOptimize(columns[2].data());
    }
    state.SetBytesProcessed(state.iterations() *
                            static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

void BM_IndexMultiFrameDump(benchmark::State& state) {
    static const std::string path = writeDump("faultline-bench-525k-x8.lammpstrj", 8);
    for (auto _ : state) {
        auto frames = indexLammpsDump(path);
        if (frames.size() != 8)
            state.SkipWithError("wrong frame count");
    }
    state.SetBytesProcessed(state.iterations() *
                            static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

void BM_ReadMultiFrameFileOnly(benchmark::State& state) {
    static const std::string path = writeDump("faultline-bench-525k-x8.lammpstrj", 8);
    std::vector<char> buffer(4 << 20);
    for (auto _ : state) {
        ByteSource source(path);
        while (source.read(buffer.data(), buffer.size()) > 0) {
        }
    }
    state.SetBytesProcessed(state.iterations() *
                            static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

} // namespace

BENCHMARK(BM_ReadFileOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FaultlineLammpsParse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_NaiveIfstreamParse)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_ReadMultiFrameFileOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_IndexMultiFrameDump)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
