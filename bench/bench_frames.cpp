// Time scrubbing: a 525,000-sphere frame from memory, from the binary frame cache (page cache
// warm and cold) and parsed from text, on a 10-frame LAMMPS dump; plus difference columns; and
// the first and the last frame parsed from the same dump gzipped (one multi-frame .gz, as LAMMPS
// writes dump.gz): the last one costs about what the first does (gzip_reader.hpp).
// The data (~270 MB text, ~210 MB cache) is made in a temp folder and deleted at the end
// (FAULTLINE_BENCH_KEEP=1 keeps it for the next run).
#include "core/data/dataset.hpp"
#include "core/data/frame_cache.hpp"
#include "core/data/frame_cache_format.hpp"
#include "core/data/frame_prefetcher.hpp"
#include "core/io/frame_source.hpp"
#include "core/model/frame_difference.hpp"
#include "core/util/malloc_huge_pages.hpp"

#include <benchmark/benchmark.h>
#include <zlib.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

using namespace faultline::core;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kSpheres = 525000;
// FAULTLINE_BENCH_FRAMES=100 makes the full 100-frame dataset (~2.7 GB text, ~2.1 GB cache).
const std::size_t kFrames = [] {
    const char* v = std::getenv("FAULTLINE_BENCH_FRAMES");
    return static_cast<std::size_t>(v ? std::max(2, std::atoi(v)) : 10);
}();

const fs::path& benchFolder() {
    static const fs::path folder = fs::temp_directory_path() / "faultline-bench-frames";
    return folder;
}

// Spheres drift and strain grows from frame to frame; every frame lists ids in its own order,
// as LAMMPS does when atoms migrate between processors.
std::string writeDump() {
    const fs::path path = benchFolder() / ("run" + std::to_string(kFrames) + ".lammpstrj");
    if (fs::exists(path))
        return path.string();
    fs::create_directories(benchFolder());
    const std::string tmp = path.string() + ".partial";
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> x(kSpheres), y(kSpheres), z(kSpheres);
    for (std::size_t i = 0; i < kSpheres; ++i) {
        x[i] = 200 * u(rng);
        y[i] = 40 * u(rng);
        z[i] = 80 * u(rng);
    }
    std::vector<std::size_t> order(kSpheres);
    std::iota(order.begin(), order.end(), 0);
    for (std::size_t t = 0; t < kFrames; ++t) {
        if (t > 0)
            std::shuffle(order.begin(), order.end(), rng);
        std::fprintf(
            f,
            "ITEM: TIMESTEP\n%zu\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS pp pp ff\n"
            "0 200\n0 40\n0 80\nITEM: ATOMS id type x y z radius strain broken_bonds layer\n",
            t * 1000, kSpheres);
        for (std::size_t i : order)
            std::fprintf(f, "%zu 1 %.5f %.5f %.5f 0.5 %.5g %d %d\n", i + 1,
                         x[i] + 0.01f * float(t) * u(rng), y[i], z[i] - 0.02f * float(t) * u(rng),
                         0.03 * double(t) * u(rng), static_cast<int>(float(t) * 1.2f * u(rng)),
                         static_cast<int>(z[i] / 10));
    }
    std::fclose(f);
    fs::rename(tmp, path);
    return path.string();
}

// The dump gzipped (level 1, as a run's dump.gz is written quickly); made once, as the dump.
std::string writeGzipDump(const std::string& dump) {
    const std::string path = dump + ".gz";
    if (fs::exists(path))
        return path;
    const std::string tmp = path + ".partial";
    std::FILE* in = std::fopen(dump.c_str(), "rb");
    gzFile out = gzopen(tmp.c_str(), "wb1");
    std::vector<char> buffer(1 << 20);
    while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), in))
        gzwrite(out, buffer.data(), static_cast<unsigned>(got));
    gzclose(out);
    std::fclose(in);
    fs::rename(tmp, path);
    return path;
}

struct Fixture {
    std::vector<FrameLocation> frames;
    std::vector<FrameLocation> gzipFrames; // indexed in this process, as Dataset::open does
    std::shared_ptr<FrameCache> cache;
    std::vector<std::string> cacheFiles;
};

Fixture& fixture() {
    static Fixture fx = [] {
        Fixture f;
        const std::string dump = writeDump();
        f.frames = indexDataFile(dump);
        f.gzipFrames = indexDataFile(writeGzipDump(dump));
        FrameCacheSettings s;
        s.folder = (benchFolder() / "cache").string();
        s.minFreeDiskBytes = 0;
        f.cache = std::make_shared<FrameCache>(s);
        for (const auto& loc : f.frames) {
            if (!f.cache->lookup(loc))
                f.cache->store(loc, loadFrame(loc));
            f.cacheFiles.push_back(f.cache->pathFor(loc));
            const int fd = ::open(f.cacheFiles.back().c_str(), O_RDONLY);
            ::fdatasync(fd); // clean pages, so a cold read can drop them
            ::close(fd);
        }
        return f;
    }();
    return fx;
}

void dropFromPageCache(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
    ::close(fd);
}

void BM_TextParse(benchmark::State& state) {
    auto& fx = fixture();
    std::size_t k = 0;
    for (auto _ : state) {
        Frame f = loadFrame(fx.frames[k++ % kFrames]);
        benchmark::DoNotOptimize(f.x.data());
    }
}

void BM_CacheWrite(benchmark::State& state) {
    auto& fx = fixture();
    const Frame frame = loadFrame(fx.frames[1]);
    const std::string path = (benchFolder() / "write-probe.flframe").string();
    for (auto _ : state)
        state.counters["MB"] = double(writeCachedFrame(path, "probe", frame)) / 1e6;
    fs::remove(path);
}

// An uncached frame: not in memory, its cache file in the OS page cache (recently used).
void BM_BinaryCacheLoadWarm(benchmark::State& state) {
    auto& fx = fixture();
    std::size_t k = 0;
    for (auto _ : state) {
        auto f = fx.cache->lookup(fx.frames[k++ % kFrames]);
        if (!f || f->size() != kSpheres)
            state.SkipWithError("cache miss");
        benchmark::DoNotOptimize(f);
    }
}

// The same with the cache file dropped from the page cache first: read from the disk.
void BM_BinaryCacheLoadCold(benchmark::State& state) {
    auto& fx = fixture();
    std::size_t k = 0;
    for (auto _ : state) {
        state.PauseTiming();
        const std::size_t i = k++ % kFrames;
        dropFromPageCache(fx.cacheFiles[i]);
        state.ResumeTiming();
        auto f = fx.cache->lookup(fx.frames[i]);
        if (!f)
            state.SkipWithError("cache miss");
        benchmark::DoNotOptimize(f);
    }
}

// A cached frame: what the UI pays each draw for a frame already in memory.
void BM_InMemoryFrame(benchmark::State& state) {
    auto& fx = fixture();
    auto ds = Dataset::open({fx.frames[0].pieces[0].path});
    ds->setFrameCache(fx.cache);
    for (std::size_t k = 0; k < kFrames; ++k)
        ds->frame(k);
    std::size_t k = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(ds->frame(k++ % kFrames));
}

void BM_PrefetcherRequestReady(benchmark::State& state) {
    auto& fx = fixture();
    auto ds = Dataset::open({fx.frames[0].pieces[0].path});
    ds->setFrameCache(fx.cache);
    for (std::size_t k = 0; k < kFrames; ++k)
        ds->frame(k);
    FramePrefetcher prefetcher(ds);
    std::size_t k = 0;
    for (auto _ : state) {
        auto r = prefetcher.request(k++ % kFrames);
        if (r.status != FrameStatus::Ready)
            state.SkipWithError("not ready");
        benchmark::DoNotOptimize(r.frame);
    }
}

// Playing forward at `fps` from an empty memory cache, frames from the disk cache: how many UI
// ticks after the first (which cannot be prefetched) found their frame not ready, and the waits.
void BM_PlaybackFromDiskCache(benchmark::State& state) {
    auto& fx = fixture();
    const auto tick = std::chrono::microseconds(1000000 / state.range(0));
    double stalls = 0, longest = 0, first = 0;
    for (auto _ : state) {
        auto ds = Dataset::open({fx.frames[0].pieces[0].path});
        ds->setFrameCache(fx.cache);
        FramePrefetcher prefetcher(ds);
        for (std::size_t k = 0; k < kFrames; ++k) {
            const auto start = std::chrono::steady_clock::now();
            if (prefetcher.request(k).status != FrameStatus::Ready) {
                while (prefetcher.request(k).status != FrameStatus::Ready)
                    std::this_thread::sleep_for(std::chrono::microseconds(200));
                const double waited = std::chrono::duration<double, std::milli>(
                                          std::chrono::steady_clock::now() - start)
                                          .count();
                if (k == 0) {
                    first = std::max(first, waited);
                } else {
                    ++stalls;
                    longest = std::max(longest, waited);
                }
            }
            std::this_thread::sleep_until(start + tick);
        }
    }
    state.counters["first_frame_ms"] = first;
    state.counters["stalls_per_pass"] = stalls / double(state.iterations());
    state.counters["longest_stall_ms"] = longest;
}

void BM_VariableChange(benchmark::State& state) {
    auto& fx = fixture();
    const Frame a = *fx.cache->lookup(fx.frames[0]);
    const Frame b = *fx.cache->lookup(fx.frames[kFrames - 1]);
    for (auto _ : state)
        benchmark::DoNotOptimize(variableChange(b, a, "broken_bonds").floats.data());
}

void BM_Displacement(benchmark::State& state) {
    auto& fx = fixture();
    const Frame a = *fx.cache->lookup(fx.frames[0]);
    const Frame b = *fx.cache->lookup(fx.frames[kFrames - 1]);
    for (auto _ : state)
        benchmark::DoNotOptimize(displacementSince(b, a).floats.data());
}

// Frame Arg (0, or -1: the last) parsed from the gzipped dump.
void BM_GzipFrameParse(benchmark::State& state) {
    auto& fx = fixture();
    const std::size_t k = state.range(0) < 0 ? kFrames - 1 : std::size_t(state.range(0));
    for (auto _ : state) {
        Frame f = loadFrame(fx.gzipFrames[k]);
        benchmark::DoNotOptimize(f.x.data());
    }
    state.SetLabel("frame " + std::to_string(k) + " of " + std::to_string(kFrames));
}

void BM_IndexDump(benchmark::State& state) {
    auto& fx = fixture();
    for (auto _ : state)
        benchmark::DoNotOptimize(indexDataFile(fx.frames[0].pieces[0].path).size());
}

} // namespace

BENCHMARK(BM_InMemoryFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PrefetcherRequestReady)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BinaryCacheLoadWarm)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_BinaryCacheLoadCold)->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK(BM_TextParse)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_GzipFrameParse)->Arg(0)->Arg(-1)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_CacheWrite)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_PlaybackFromDiskCache)->Arg(10)->Arg(24)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_VariableChange)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Displacement)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IndexDump)->Unit(benchmark::kMillisecond)->Iterations(3);

int main(int argc, char** argv) {
    faultline::core::restartWithMallocHugePages(argv); // as faultline-app runs
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    if (!std::getenv("FAULTLINE_BENCH_KEEP"))
        fs::remove_all(benchFolder());
    return 0;
}
