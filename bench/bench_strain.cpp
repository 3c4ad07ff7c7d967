// Strain from motion (issue 36), a timed run in one process:
//  1. 525,000 spheres in a dense packing (jittered hexagonal close packing, ~20 neighbours within
//     the default cutoff) cut by three thick normal-fault zones, two frames written as a LAMMPS
//     text dump with the second frame's rows in another order (as LAMMPS writes them): opening
//     frame 1 (parsed from text, and from the binary frame cache) against computing its strain
//     against frame 0 (strainFromMotion, and through the dataset with strain.add's spec).
//  2. 10,000,000 spheres of the same kind in memory: the strain's time and the extra memory it
//     takes (peak resident set growth, per sphere).
//  3. With --demo: scrubbing the 3-D demo (frames 4..39, each new) with and without incremental
//     strain (since_offset -4), each frame's time; and how long the workbench's background pass
//     takes to derive every frame into the frame cache.
// Usage: bench_strain [--skip-10m] [--demo], bench_strain --demo-only (part 3 alone), or
// bench_strain --strain-only N: strainFromMotion alone on the 525k pair, N times with the vector
// sums (AVX-512 or AVX2, as the CPU has them) and with the baseline ones (for a profiler and to
// compare the two; FAULTLINE_BENCH_AVX2_ONLY=1: the vector sums only; FAULTLINE_BENCH_EVICT=1:
// caches flushed before each run; FAULTLINE_BENCH_SHUFFLED_REFERENCE=1: the reference frame's rows
// in no order too); or bench_strain --demo-strain-only N: strainFromMotion alone on two of the
// demo's frames; or bench_strain --dump FILE [FROM TO]: a file's frame TO parsed against its strain
// against frame FROM (e.g. the real run examples/lammps/tile.sh has LAMMPS tile to 527k grains).
// The dumps
// (~42 MB plain, and gzipped) are made in a temp folder and deleted at the end.
// FAULTLINE_BENCH_NO_AVX512=1 (any part): the AVX2 sums where the CPU has AVX-512 too.
#include "core/data/dataset.hpp"
#include "core/data/frame_cache.hpp"
#include "core/data/frame_prefetcher.hpp"
#include "core/motion/strain_from_motion.hpp"
#include "core/synth/demo_model.hpp"
#include "core/synth/dump_writer.hpp"
#include "core/util/malloc_huge_pages.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

using namespace faultline::core;
namespace fs = std::filesystem;

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Resident set now (kB), from /proc/self/statm.
long residentKb() {
    std::ifstream in("/proc/self/statm");
    long size = 0, resident = 0;
    in >> size >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

long peakKb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

// The peak resident set since the last resetPeak (kB; VmHWM of /proc/self/status), and its reset
// (Linux: "5" to /proc/self/clear_refs); false where the kernel does not offer the reset.
long highWaterKb() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmHWM:", 0) == 0)
            return std::atol(line.c_str() + 6);
    return 0;
}
bool resetPeak() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return bool(out);
}

// About `n` spheres of radius 0.5 in hexagonal close packing, jittered by 0.05, in a block twice
// as long (x) as it is high (z) and half as deep (y).
Frame densePacking(std::size_t n) {
    const double r = 0.5, dy = 2 * r * std::sqrt(2.0 / 3.0), dz = r * std::sqrt(3.0);
    // columns * layers * rows = n with columns : layers : rows spacing-weighted 4 : 1 : 2.
    const double unit = std::cbrt(double(n) * (2 * r) * dy * dz / 8.0);
    const int columns = std::max(2, int(4 * unit / (2 * r)));
    const int layers = std::max(2, int(1 * unit / dy));
    const int rows = std::max(2, int(std::ceil(double(n) / (double(columns) * layers))));
    Frame f;
    f.ids.reserve(n);
    f.x.reserve(n);
    f.y.reserve(n);
    f.z.reserve(n);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    for (int row = 0; row < rows && f.ids.size() < n; ++row)
        for (int l = 0; l < layers && f.ids.size() < n; ++l)
            for (int c = 0; c < columns && f.ids.size() < n; ++c) {
                f.ids.push_back(static_cast<std::int64_t>(f.ids.size()) + 1);
                f.x.push_back(float(r * (1 + 2 * c + (row & 1) + (l & 1))) + jitter(rng));
                f.y.push_back(float(r * 1 + l * dy) + jitter(rng));
                f.z.push_back(float(r * 1 + row * dz + (l & 1) * r / std::sqrt(3.0)) + jitter(rng));
            }
    f.radius.assign(f.ids.size(), float(r));
    f.box.known = true;
    f.box.lo = {0, 0, 0};
    f.box.hi = {r * (2 * columns + 2), layers * dy, rows * dz + r};
    f.box.periodic = {false, true, false};
    f.finalize();
    return f;
}

// Three normal-fault zones, each 3 diameters thick, dipping 60 degrees, spread along the block:
// the hanging wall of each slides 0.4 down-dip, ramping across the zone; small noise elsewhere.
// Rows in a shuffled order.
Frame faulted(const Frame& ref) {
    const double length = ref.box.hi[0], height = ref.box.hi[2];
    const double dip = 60 * M_PI / 180, nx = std::sin(dip), nz = std::cos(dip);
    const double sx = -std::cos(dip), sz = -std::sin(dip); // down-dip, dipping east... then west
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> noise(-0.01f, 0.01f);
    std::vector<std::size_t> order(ref.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    Frame f;
    f.box = ref.box;
    f.ids.reserve(ref.size());
    for (std::size_t i : order) {
        double x = ref.x[i], z = ref.z[i];
        for (int k = 0; k < 3; ++k) {
            const double x0 = length * (0.25 + 0.25 * k), sign = k == 1 ? -1.0 : 1.0;
            // Signed distance from the plane through (x0, height/2).
            const double d = (x - x0) * nx * sign + (z - height / 2) * nz;
            const double w = std::clamp(d / 3.0 + 0.5, 0.0, 1.0); // 0 footwall, 1 hanging wall
            x += 0.4 * w * sx * sign;
            z += 0.4 * w * sz;
        }
        f.ids.push_back(ref.ids[i]);
        f.x.push_back(float(x) + noise(rng));
        f.y.push_back(ref.y[i] + noise(rng));
        f.z.push_back(float(z) + noise(rng));
        f.radius.push_back(ref.radius[i]);
    }
    f.finalize();
    return f;
}

// `f` with its rows in a random order.
Frame shuffled(const Frame& f) {
    std::vector<std::size_t> order(f.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(11));
    Frame out;
    out.box = f.box;
    for (std::size_t i : order) {
        out.ids.push_back(f.ids[i]);
        out.x.push_back(f.x[i]);
        out.y.push_back(f.y[i]);
        out.z.push_back(f.z[i]);
        out.radius.push_back(f.radius[i]);
    }
    out.finalize();
    return out;
}

void part525k() {
    const fs::path dir = fs::temp_directory_path() / "faultline-bench-strain";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Frame ref = densePacking(525000);
    const Frame now = faulted(ref);
    const std::string dump = (dir / "two.lammpstrj").string();
    const std::string gz = (dir / "two.lammpstrj.gz").string(); // as LAMMPS' dump custom/gz
    for (const auto& [path, level] : {std::pair{dump, 0}, std::pair{gz, 6}}) {
        LammpsDumpWriter w(path, level);
        w.write(ref, {"id", "x", "y", "z", "radius"});
        w.write(now, {"id", "x", "y", "z", "radius"});
        w.close();
    }
    std::printf("525k: %zu spheres, dump %.1f MB, default cutoff %.3f\n", ref.size(),
                double(fs::file_size(dump)) / 1e6, defaultStrainCutoff(ref));

    FrameCacheSettings settings;
    settings.folder = (dir / "cache").string();
    settings.minFreeDiskBytes = 0;
    auto cache = std::make_shared<FrameCache>(settings);
    double parse = 0, parseGz = 0, cached = 0, strain = 0, derived = 0;
    double coldStrain = 0, coldParse = 0; // the first round: nothing in the scratch pool yet
    // Rounds of both, each ratio taken within its round: this machine's speed drifts by a third
    // within minutes, and a median of five moved by 0.2 from one run to the next.
    const int rounds = 11;
    std::vector<double> ratios;
    for (int round = 0; round < rounds; ++round) {
        // Parsed from text (no cache), then written to and read from the binary cache.
        auto plain = Dataset::open({dump});
        plain->setFrameCache(nullptr);
        auto t0 = std::chrono::steady_clock::now();
        auto f1 = plain->frame(1);
        const double p = seconds(t0);
        auto f0 = plain->frame(0);
        auto zipped = Dataset::open({gz});
        zipped->setFrameCache(nullptr);
        t0 = std::chrono::steady_clock::now();
        zipped->frame(1);
        const double z = seconds(t0);
        parseGz += z / rounds;
        auto withCache = Dataset::open({dump});
        withCache->setFrameCache(cache);
        withCache->frame(1); // fills the cache (first round) or reads it
        auto again = Dataset::open({dump});
        again->setFrameCache(cache);
        t0 = std::chrono::steady_clock::now();
        again->frame(1);
        const double c = seconds(t0);
        t0 = std::chrono::steady_clock::now();
        auto cols = strainFromMotion(*f1, *f0, 0);
        const double s = seconds(t0);
        // Through the dataset: frame 1 derived with the spec (frame 0 and 1 cached as read).
        plain->setStrains({StrainSpec{false, 0, 0, ""}});
        t0 = std::chrono::steady_clock::now();
        auto d = plain->frame(1);
        const double ds = seconds(t0);
        parse += p / rounds;
        cached += c / rounds;
        strain += s / rounds;
        derived += ds / rounds;
        ratios.push_back(s / p);
        if (round == 0) {
            coldStrain = s;
            coldParse = p;
            std::size_t nan = 0, high = 0;
            for (float v : cols[0].floats) {
                nan += std::isnan(v) ? 1 : 0;
                high += v > 0.05f ? 1 : 0;
            }
            std::printf("  shear_strain: %zu NaN, %zu above 0.05 (in the three zones)\n", nan,
                        high);
        }
    }
    std::sort(ratios.begin(), ratios.end());
    std::printf("  open frame 1, parsed from text:     %7.1f ms (mean of %d)\n", parse * 1e3,
                rounds);
    std::printf("  open frame 1, parsed from gzip:     %7.1f ms\n", parseGz * 1e3);
    std::printf("  open frame 1, binary frame cache:   %7.1f ms\n", cached * 1e3);
    std::printf("  strainFromMotion against frame 0:   %7.1f ms\n", strain * 1e3);
    std::printf("  dataset frame 1 with strain.add:    %7.1f ms (copy + strain)\n", derived * 1e3);
    std::printf("  first round (scratch pool empty): strain %.1f ms, parse %.1f ms\n",
                coldStrain * 1e3, coldParse * 1e3);
    std::printf("  strain / parse: median %.2f (rounds %.2f to %.2f); strain / gzip parse: %.2f; "
                "strain / cache read: %.2f\n",
                ratios[ratios.size() / 2], ratios.front(), ratios.back(), strain / parseGz,
                strain / cached);
    fs::remove_all(dir);
}

void part10m() {
    const long before = residentKb();
    Frame ref = densePacking(10000000);
    Frame now = faulted(ref);
    const long frames = residentKb();
    const long peakBefore = peakKb();
    auto t0 = std::chrono::steady_clock::now();
    auto cols = strainFromMotion(now, ref, 0);
    const double s = seconds(t0);
    const long peakAfter = peakKb();
    std::printf("10M: %zu spheres: frames take %.0f MB; strain %.2f s; peak resident growth "
                "%.0f MB = %.1f bytes per sphere (of which the %zu result columns: %zu)\n",
                ref.size(), double(frames - before) / 1024, s,
                double(peakAfter - std::max(peakBefore, frames)) / 1024,
                double(peakAfter - std::max(peakBefore, frames)) * 1024 / double(ref.size()),
                cols.size(), cols.size() * sizeof(float));
}

void partDemo() {
    const std::string file = ensureDemoModel();
    // A private frame cache, so the first scrub with strain derives every frame.
    const fs::path folder = fs::temp_directory_path() / "faultline-bench-strain-demo";
    fs::remove_all(folder);
    FrameCacheSettings settings;
    settings.folder = folder.string();
    settings.minFreeDiskBytes = 0;
    auto cache = std::make_shared<FrameCache>(settings);
    auto opened = [&](bool withStrain) {
        auto ds = Dataset::open({file});
        ds->setFrameCache(cache);
        if (withStrain)
            ds->setStrains({StrainSpec{true, -4, 0, "inc_"}});
        return ds;
    };
    // Until the frame is in memory for the view (a frame derived now is written to the frame
    // cache after that, on the loading thread, as the workbench's prefetcher does).
    auto timed = [](const Dataset& ds, std::size_t k) {
        const auto t0 = std::chrono::steady_clock::now();
        double ready = 0;
        ds.frame(k, [&] { ready = seconds(t0); });
        return ready;
    };
    // Each frame without strain then with it, one after the other: both meet the same heap.
    // (Scrubbed one whole pass after the other, the first frames of one pass reuse memory the
    // last pass freed and those of the other fault fresh pages in: 3 ms against 9 ms a frame
    // here, whatever the strain.)
    auto scrubBoth = [&]() {
        std::pair<std::vector<double>, std::vector<double>> times;
        auto plainDs = opened(false), strainDs = opened(true);
        for (std::size_t k = 4; k < plainDs->frameCount(); ++k) {
            // Which goes first alternates: neither always follows the other's cache write.
            if (k % 2 == 0)
                times.first.push_back(timed(*plainDs, k));
            times.second.push_back(timed(*strainDs, k));
            if (k % 2 == 1)
                times.first.push_back(timed(*plainDs, k));
        }
        return times;
    };
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    {
        auto ds = opened(false); // parses into the cache
        for (std::size_t k = 0; k < ds->frameCount(); ++k)
            ds->frame(k);
    }
    const auto [plain, first] = scrubBoth();   // derives each frame (and caches it)
    const auto [plain2, cached] = scrubBoth(); // the derived frames from the cache
    for (const auto& [what, times, without] :
         {std::tuple{"derived (first time)", first, plain},
          std::tuple{"derived, from the cache", cached, plain2}}) {
        std::vector<double> ratios;
        for (std::size_t k = 0; k < without.size(); ++k)
            ratios.push_back(times[k] / without[k]);
        const std::size_t worst =
            std::size_t(std::max_element(ratios.begin(), ratios.end()) - ratios.begin());
        std::printf("demo scrub, frames 4..%zu each new, incremental strain %s: median frame "
                    "%.1f ms against %.1f ms without strain; ratio median %.2f, worst %.2f "
                    "(frame %zu: %.1f ms against %.1f ms)\n",
                    without.size() + 3, what, median(times) * 1e3, median(without) * 1e3,
                    median(ratios), ratios[worst], worst + 4, times[worst] * 1e3,
                    without[worst] * 1e3);
        if (std::getenv("FAULTLINE_BENCH_FRAMES"))
            for (std::size_t k = 0; k < ratios.size(); ++k)
                std::printf("  frame %zu: %.1f ms against %.1f ms\n", k + 4, times[k] * 1e3,
                            without[k] * 1e3);
    }
    fs::remove_all(folder);

    // As the workbench scrubs: through a FramePrefetcher (the next frames loaded, and their
    // strain derived, on worker threads while the user looks at this one), a new frame every
    // `pace` (a fast drag of the timeline: 10 frames a second; a play at 5 fps is 200 ms). The
    // figure is how long each new frame kept the view waiting after it was asked for, with
    // incremental strain derived for the first time against plain frames.
    for (const int paceMs : {100, 200}) {
        auto paced = [&](bool withStrain) {
            fs::remove_all(folder);
            auto cache2 = std::make_shared<FrameCache>(settings);
            auto ds = Dataset::open({file});
            ds->setFrameCache(cache2);
            for (std::size_t k = 0; k < ds->frameCount(); ++k)
                ds->frame(k); // parsed into the cache: both runs read binary frames
            ds = Dataset::open({file});
            ds->setFrameCache(cache2);
            if (withStrain)
                ds->setStrains({StrainSpec{true, -4, 0, "inc_"}});
            FramePrefetcher prefetcher(ds);
            std::vector<double> waits;
            for (std::size_t k = 4; k < ds->frameCount(); ++k) {
                const auto t0 = std::chrono::steady_clock::now();
                while (prefetcher.request(k, 0).status != FrameStatus::Ready)
                    std::this_thread::sleep_for(std::chrono::microseconds(200));
                waits.push_back(seconds(t0));
                std::this_thread::sleep_until(t0 + std::chrono::milliseconds(paceMs));
            }
            prefetcher.waitIdle(std::chrono::seconds(60));
            return waits;
        };
        const auto plainWaits = paced(false);
        const auto strainWaits = paced(true);
        // The first frame asked for has nothing prefetched: it is derived on the spot (the
        // figure above); the worst of the frames after it is what the prefetcher gains.
        auto worstAfterFirst = [](const std::vector<double>& w) {
            return w.size() < 2 ? 0.0 : *std::max_element(w.begin() + 1, w.end());
        };
        std::printf("demo scrub through the prefetcher, a new frame every %d ms: wait per frame "
                    "median %.1f ms (worst %.1f) with incremental strain derived for the first "
                    "time, %.1f ms (worst %.1f) without\n",
                    paceMs, median(strainWaits) * 1e3,
                    *std::max_element(strainWaits.begin(), strainWaits.end()) * 1e3,
                    median(plainWaits) * 1e3,
                    *std::max_element(plainWaits.begin(), plainWaits.end()) * 1e3);
        std::printf("  the first frame %.1f ms against %.1f ms without strain; the %zu after it "
                    "worst %.1f ms against %.1f ms\n",
                    strainWaits.front() * 1e3, plainWaits.front() * 1e3, strainWaits.size() - 1,
                    worstAfterFirst(strainWaits) * 1e3, worstAfterFirst(plainWaits) * 1e3);
    }
    // As the workbench does after strain.add: while the view idles on one frame, the background
    // pass derives every frame into the frame cache (a scrub after it reads derived frames: the
    // "from the cache" figure above).
    {
        fs::remove_all(folder);
        auto cache3 = std::make_shared<FrameCache>(settings);
        auto ds = Dataset::open({file});
        ds->setFrameCache(cache3);
        for (std::size_t k = 0; k < ds->frameCount(); ++k)
            ds->frame(k); // parsed into the cache, as in the runs above
        ds = Dataset::open({file});
        ds->setFrameCache(cache3);
        ds->setStrains({StrainSpec{true, -4, 0, "inc_"}});
        FramePrefetcher prefetcher(ds);
        prefetcher.setBackgroundDerivation(true);
        const auto t0 = std::chrono::steady_clock::now();
        while (prefetcher.request(4, 0).status != FrameStatus::Ready)
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        for (;;) {
            const auto p = prefetcher.backgroundProgress();
            if (p.done == p.total && !p.running)
                break;
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        const double total = seconds(t0);
        std::printf("demo, background pass after strain.add (the view idle on frame 4): all %zu "
                    "frames derived into the frame cache %.2f s after it, %.1f ms a frame\n",
                    ds->frameCount(), total, total * 1e3 / double(ds->frameCount()));
    }
    fs::remove_all(folder);
}

} // namespace

int main(int argc, char** argv) {
    faultline::core::restartWithMallocHugePages(argv); // as faultline-app runs
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    std::printf("malloc huge pages: %s (as faultline-app; FAULTLINE_HUGE_PAGES=0: off)\n",
                tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb=1") ? "on"
                                                                                       : "off");
    bool skip10m = false, demo = false, demoOnly = false;
    if (const char* no512 = std::getenv("FAULTLINE_BENCH_NO_AVX512"); no512 && *no512 == '1')
        detail::setStrainAvx512Allowed(false);
    std::printf("neighbour sums: %s\n", detail::strainUsesAvx512() ? "AVX-512"
                                        : detail::strainUsesAvx2() ? "AVX2"
                                                                   : "baseline");
    for (int k = 1; k < argc; ++k) {
        skip10m = skip10m || std::strcmp(argv[k], "--skip-10m") == 0;
        demo = demo || std::strcmp(argv[k], "--demo") == 0;
        demoOnly = demoOnly || std::strcmp(argv[k], "--demo-only") == 0;
    }
    for (int k = 1; k + 1 < argc; ++k)
        if (std::strcmp(argv[k], "--demo-strain-only") == 0) {
            // strainFromMotion alone on the demo's frames 39 against 35 (incremental strain at
            // -4), N times, against reading frame 39 from the binary frame cache.
            auto ds = Dataset::open({ensureDemoModel()});
            const auto now = ds->frame(39), ref = ds->frame(35);
            std::vector<double> times;
            for (int r = std::max(1, std::atoi(argv[k + 1])); r > 0; --r) {
                const auto t0 = std::chrono::steady_clock::now();
                strainFromMotion(*now, *ref, 0);
                times.push_back(seconds(t0) * 1e3);
            }
            std::sort(times.begin(), times.end());
            std::printf("demo strain (%zu spheres): fastest %.1f ms, median %.1f ms of %zu\n",
                        now->size(), times.front(), times[times.size() / 2], times.size());
            return 0;
        }
    for (int k = 1; k + 1 < argc; ++k)
        if (std::strcmp(argv[k], "--dump") == 0) {
            // A user's own data (any file Faultline reads, e.g. a LAMMPS dump): opening frame TO
            // (parsed, no frame cache) against its strain against frame FROM (default 0 and 1),
            // in rounds, each ratio taken within its round, as part 1 does for the 525k block.
            const std::string path = argv[k + 1];
            const std::size_t from = k + 2 < argc ? std::size_t(std::atoll(argv[k + 2])) : 0;
            const std::size_t to = k + 3 < argc ? std::size_t(std::atoll(argv[k + 3])) : 1;
            std::vector<double> parses, strains, ratios;
            std::size_t spheres = 0;
            try {
                for (int round = 0; round < 11; ++round) {
                    auto ds = Dataset::open({path}); // the frames parsed again each round
                    ds->setFrameCache(nullptr);
                    auto t0 = std::chrono::steady_clock::now();
                    const auto now = ds->frame(to);
                    const double p = seconds(t0);
                    const auto ref = ds->frame(from);
                    // The first round's extra memory (nothing in the scratch pool yet): the
                    // peak resident set during the strain over the resident set before it.
                    const bool peakReset = round == 0 && resetPeak();
                    const long residentBefore = residentKb();
                    t0 = std::chrono::steady_clock::now();
                    const auto cols = strainFromMotion(*now, *ref, 0);
                    const double s = seconds(t0);
                    spheres = now->size();
                    const long growthKb = peakReset ? highWaterKb() - residentBefore : -1;
                    if (round == 0) {
                        std::size_t nan = 0;
                        for (float v : cols[0].floats)
                            nan += std::isnan(v) ? 1 : 0;
                        std::printf("%s: frame %zu against %zu, %zu spheres (%zu without a "
                                    "value), default cutoff %.3f\n",
                                    path.c_str(), to, from, spheres, nan,
                                    defaultStrainCutoff(*ref));
                        if (growthKb >= 0)
                            std::printf("  first round: strain %.1f ms, peak resident growth "
                                        "%.0f MB = %.1f bytes per sphere\n",
                                        s * 1e3, double(growthKb) / 1024,
                                        double(growthKb) * 1024 /
                                            double(std::max<std::size_t>(1, spheres)));
                    }
                    parses.push_back(p * 1e3);
                    strains.push_back(s * 1e3);
                    ratios.push_back(s / p);
                }
            } catch (const std::exception& e) {
                std::fprintf(stderr, "%s\n", e.what());
                return 1;
            }
            for (auto* v : {&parses, &strains, &ratios})
                std::sort(v->begin(), v->end());
            std::printf("  open frame %zu, parsed: median %.1f ms; strainFromMotion: median %.1f "
                        "ms (fastest %.1f)\n  strain / parse: median %.2f (rounds %.2f to %.2f)\n",
                        to, parses[5], strains[5], strains.front(), ratios[5], ratios.front(),
                        ratios.back());
            return 0;
        }
    for (int k = 1; k + 1 < argc; ++k)
        if (std::strcmp(argv[k], "--strain-only") == 0) {
            // Only strainFromMotion on the 525k pair, N times (for a profiler).
            // FAULTLINE_BENCH_SHUFFLED_REFERENCE=1: the reference's rows in no order too, as
            // LAMMPS writes them when several processes run.
            const char* shuffledEnv = std::getenv("FAULTLINE_BENCH_SHUFFLED_REFERENCE");
            const Frame packed = densePacking(525000);
            const Frame ref =
                shuffledEnv && std::strcmp(shuffledEnv, "1") == 0 ? shuffled(packed) : packed;
            const Frame now = faulted(ref);
            std::vector<double> times[2];
            // FAULTLINE_BENCH_EVICT=1: 64 MB written before each run, so the frames come from
            // memory rather than the caches, as just after a frame was opened.
            const char* evictEnv = std::getenv("FAULTLINE_BENCH_EVICT");
            std::vector<char> evict(evictEnv && std::strcmp(evictEnv, "1") == 0 ? 64 << 20 : 0);
            for (int r = std::max(1, std::atoi(argv[k + 1])); r > 0; --r)
                for (const bool baseline : {false, true}) {
                    if (const char* only = std::getenv("FAULTLINE_BENCH_AVX2_ONLY");
                        baseline && only && std::strcmp(only, "1") == 0)
                        continue;
                    std::fill(evict.begin(), evict.end(), char(r));
                    detail::setStrainBaselineOnly(baseline);
                    const auto t0 = std::chrono::steady_clock::now();
                    strainFromMotion(now, ref, 0);
                    times[baseline].push_back(seconds(t0) * 1e3);
                }
            detail::setStrainBaselineOnly(false);
            for (const bool baseline : {false, true}) {
                auto& t = times[baseline];
                if (t.empty())
                    continue;
                std::sort(t.begin(), t.end());
                std::printf("strain, %s sums: fastest %.1f ms, median %.1f ms of %zu\n",
                            baseline                     ? "baseline"
                            : detail::strainUsesAvx512() ? "AVX-512"
                            : detail::strainUsesAvx2()   ? "AVX2"
                                                         : "baseline (no AVX2 here)",
                            t.front(), t[t.size() / 2], t.size());
            }
            return 0;
        }
    if (demo || demoOnly)
        partDemo();
    if (demoOnly)
        return 0;
    part525k();
    if (!skip10m)
        part10m();
    return 0;
}
