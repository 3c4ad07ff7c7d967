// Selection speed on 1,000,000 random spheres with 6 attributes: visibility after one threshold
// change, 256-bin histograms of all + visible, and a plain single-threaded array-of-structs loop
// doing the same work, measured in the same run (issue 4 asks for that baseline beside ours).
#include "core/model/frame_difference.hpp"
#include "core/selection/histogram.hpp"
#include "core/selection/visibility.hpp"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <random>

using namespace faultline::core;

namespace {

constexpr std::size_t kSpheres = 1'000'000;
constexpr int kAttributes = 6;
const char* const kNames[kAttributes] = {"strain",   "stress",       "damage",
                                         "porosity", "broken_bonds", "layer"};

// The baseline's layout: one struct per sphere.
struct Particle {
    std::int64_t id;
    float x, y, z, r;
    float attrs[kAttributes];
};

struct Data {
    std::shared_ptr<const Frame> frame;
    std::vector<Particle> particles;
    std::vector<CuttingBox> boxes;
    std::vector<VariableThreshold> thresholds;
    std::vector<std::uint8_t> visibleMask; // for the histogram benches
};

const Data& data() {
    static const Data d = [] {
        Data d;
        std::mt19937 rng(42);
        std::uniform_real_distribution<float> pos(0.0f, 10.0f);
        std::exponential_distribution<float> strain(20.0f);
        std::normal_distribution<float> stress(50.0f, 10.0f);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::geometric_distribution<int> broken(0.4);
        std::uniform_int_distribution<int> layer(0, 9);

        auto f = std::make_shared<Frame>();
        std::vector<std::vector<float>> cols(kAttributes, std::vector<float>(kSpheres));
        d.particles.resize(kSpheres);
        for (std::size_t i = 0; i < kSpheres; ++i) {
            Particle& p = d.particles[i];
            p.id = static_cast<std::int64_t>(i + 1);
            p.x = pos(rng);
            p.y = pos(rng);
            p.z = pos(rng);
            p.r = 0.05f;
            p.attrs[0] = strain(rng);
            p.attrs[1] = stress(rng);
            p.attrs[2] = unit(rng);
            p.attrs[3] = 0.3f * unit(rng);
            p.attrs[4] = float(std::min(broken(rng), 12));
            p.attrs[5] = float(layer(rng));
            f->ids.push_back(p.id);
            f->x.push_back(p.x);
            f->y.push_back(p.y);
            f->z.push_back(p.z);
            f->radius.push_back(p.r);
            for (int a = 0; a < kAttributes; ++a)
                cols[a][i] = p.attrs[a];
        }
        for (int a = 0; a < kAttributes; ++a)
            f->attributes.push_back(makeAttribute(kNames[a], std::move(cols[a]), a >= 4));
        f->finalize();
        d.frame = f;

        CuttingBox keep;
        keep.name = "block";
        keep.min = {1, 1, 1};
        keep.max = {9, 9, 9};
        CuttingBox cut;
        cut.name = "core";
        cut.mode = BoxMode::Cut;
        cut.min = {4, 4, 4};
        cut.max = {6, 6, 6};
        d.boxes = {keep, cut};
        auto t = [](const char* v, double lo, double hi) {
            VariableThreshold th;
            th.variable = v;
            th.low = lo;
            th.high = hi;
            return th;
        };
        // Permissive, so that most rows reach every test.
        d.thresholds = {t("strain", 0.001, 1e30), t("stress", 20, 80),      t("damage", 0.02, 0.98),
                        t("porosity", 0.01, 0.3), t("broken_bonds", 0, 10), t("layer", 1, 9)};
        d.visibleMask = computeVisibility(*d.frame, d.boxes, d.thresholds).mask;
        return d;
    }();
    return d;
}

tbb::global_control threads(const benchmark::State& state) {
    return tbb::global_control(tbb::global_control::max_allowed_parallelism,
                               static_cast<std::size_t>(state.range(0)));
}

// (a) The interactive path: one threshold moved, the mask and count recomputed.
void visibilityBench(benchmark::State& state, const std::vector<std::uint8_t>* rowMask) {
    const Data& d = data();
    const auto control = threads(state);
    auto thresholds = d.thresholds;
    std::size_t i = 0, visible = 0;
    for (auto _ : state) {
        thresholds[0].low = (++i % 2) ? 0.002 : 0.001; // a new value every time
        const VisibilityResult r = computeVisibility(*d.frame, d.boxes, thresholds, rowMask);
        visible = r.visibleCount;
        benchmark::DoNotOptimize(visible);
    }
    state.counters["visible"] = double(visible);
}
void BM_Visibility_OneThresholdChange(benchmark::State& state) { visibilityBench(state, nullptr); }
// The same with a fault filter (row mask) hiding every third sphere.
void BM_Visibility_OneThresholdChange_RowMask(benchmark::State& state) {
    static const std::vector<std::uint8_t> rowMask = [] {
        std::vector<std::uint8_t> m(kSpheres);
        for (std::size_t i = 0; i < kSpheres; ++i)
            m[i] = i % 3 != 0;
        return m;
    }();
    visibilityBench(state, &rowMask);
}
BENCHMARK(BM_Visibility_OneThresholdChange)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Visibility_OneThresholdChange_RowMask)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// (b) 256 bins, all + visible in one pass, binning chosen once (as the UI caches it).
void histogramBench(benchmark::State& state, const char* variable) {
    const Data& d = data();
    const auto control = threads(state);
    const ColumnView column = *findColumn(*d.frame, variable);
    HistogramSpec spec;
    spec.bins = 256;
    const HistogramBinning binning = chooseBinning(column, spec);
    for (auto _ : state) {
        const Histogram h = computeHistogram(column, binning, &d.visibleMask);
        benchmark::DoNotOptimize(h.all.bins.data());
    }
}
void BM_Histogram256_AllAndVisible_Float(benchmark::State& state) {
    histogramBench(state, "stress");
}
void BM_Histogram256_AllAndVisible_Int(benchmark::State& state) {
    histogramBench(state, "broken_bonds");
}
BENCHMARK(BM_Histogram256_AllAndVisible_Float)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Histogram256_AllAndVisible_Int)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Automatic (Freedman-Diaconis) binning: the quartile selection, paid once per variable.
void BM_ChooseBinning_FreedmanDiaconis(benchmark::State& state) {
    const Data& d = data();
    const ColumnView column = *findColumn(*d.frame, "stress");
    for (auto _ : state)
        benchmark::DoNotOptimize(chooseBinning(column).bins);
}
BENCHMARK(BM_ChooseBinning_FreedmanDiaconis)->Unit(benchmark::kMillisecond);

// A view's "percentile" colour range (1st to 99th percentile of the spheres shown), worked out
// on the UI thread once per new frame or visibility.
void BM_ColourRangePercentiles_Visible(benchmark::State& state) {
    const Data& d = data();
    for (auto _ : state)
        benchmark::DoNotOptimize(maskedQuantiles(*d.frame, "stress", d.visibleMask, 0.01, 0.99));
}
BENCHMARK(BM_ColourRangePercentiles_Visible)->Unit(benchmark::kMillisecond);

// (c) Baseline: a plain single-threaded loop over an array of structs, same rule, same output.
void BM_Baseline_AoS_Visibility(benchmark::State& state) {
    const Data& d = data();
    auto thresholds = d.thresholds;
    std::vector<std::uint8_t> mask(kSpheres);
    std::size_t i = 0, visible = 0;
    for (auto _ : state) {
        thresholds[0].low = (++i % 2) ? 0.002 : 0.001;
        visible = 0;
        for (std::size_t row = 0; row < kSpheres; ++row) {
            const Particle& p = d.particles[row];
            bool anyKeep = false, inKeep = false, inCut = false;
            for (const CuttingBox& b : d.boxes) {
                if (!b.enabled)
                    continue;
                anyKeep |= b.mode == BoxMode::Keep;
                if (b.contains(p.x, p.y, p.z))
                    (b.mode == BoxMode::Keep ? inKeep : inCut) = true;
            }
            bool pass = (!anyKeep || inKeep) && !inCut;
            for (int a = 0; a < kAttributes && pass; ++a)
                pass = thresholds[a].passes(p.attrs[a]);
            mask[row] = pass;
            visible += pass;
        }
        benchmark::DoNotOptimize(mask.data());
    }
    state.counters["visible"] = double(visible);
}
BENCHMARK(BM_Baseline_AoS_Visibility)->Unit(benchmark::kMillisecond);

void BM_Baseline_AoS_Histogram256(benchmark::State& state) {
    const Data& d = data();
    const int attr = 1; // stress
    double lo = 1e300, hi = -1e300;
    for (const Particle& p : d.particles) {
        lo = std::min(lo, double(p.attrs[attr]));
        hi = std::max(hi, double(p.attrs[attr]));
    }
    const int bins = 256;
    const double scale = bins / (hi - lo);
    std::vector<std::uint64_t> all(bins), visible(bins);
    std::uint64_t nan = 0;
    for (auto _ : state) {
        std::fill(all.begin(), all.end(), 0);
        std::fill(visible.begin(), visible.end(), 0);
        nan = 0;
        for (std::size_t row = 0; row < kSpheres; ++row) {
            const double v = d.particles[row].attrs[attr];
            if (std::isnan(v)) {
                ++nan;
                continue;
            }
            if (v < lo || v > hi)
                continue;
            const int k = std::min(bins - 1, static_cast<int>((v - lo) * scale));
            ++all[k];
            if (d.visibleMask[row])
                ++visible[k];
        }
        benchmark::DoNotOptimize(all.data());
        benchmark::DoNotOptimize(visible.data());
    }
}
BENCHMARK(BM_Baseline_AoS_Histogram256)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
