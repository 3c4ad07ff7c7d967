#include "core/selection/histogram.hpp"

#include "core/selection/row_bits.hpp"
#include "core/util/quantile.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace faultline::core {

namespace {

constexpr std::size_t kGrainRows = 16384;

template <typename T, typename F> void forEachValue(const ColumnView& column, F&& f) {
    const T* values;
    if constexpr (std::is_same_v<T, float>)
        values = column.floats;
    else
        values = column.ints;
    for (std::size_t i = 0; i < column.size; ++i)
        f(values[i]);
}

// Finite min and max; nullopt when there is no finite value.
std::optional<std::array<double, 2>> finiteRange(const ColumnView& column) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    auto see = [&](auto v) {
        const double d = static_cast<double>(v);
        if (std::isfinite(d)) {
            lo = std::min(lo, d);
            hi = std::max(hi, d);
        }
    };
    if (column.isInteger())
        forEachValue<std::int32_t>(column, see);
    else
        forEachValue<float>(column, see);
    if (lo > hi)
        return std::nullopt;
    return std::array<double, 2>{lo, hi};
}

int freedmanDiaconisBins(const ColumnView& column, double lo, double hi) {
    assert(!column.isInteger()); // integer columns get integer bins
    std::vector<float> finite;
    finite.reserve(column.size);
    forEachValue<float>(column, [&](float v) {
        if (std::isfinite(v))
            finite.push_back(v);
    });
    const std::size_t n = finite.size();
    if (n == 0)
        return 1;
    double iqr = 0.0;
    if (n >= 2) {
        const double q1 = quantile(finite, 0.25);
        const double q3 = quantile(finite, 0.75);
        iqr = q3 - q1;
    }
    double bins;
    if (iqr > 0.0) {
        const double width = 2.0 * iqr / std::cbrt(static_cast<double>(n));
        bins = std::ceil((hi - lo) / width);
    } else {
        bins = std::ceil(std::log2(static_cast<double>(n))) + 1.0; // Sturges
    }
    return static_cast<int>(std::clamp(bins, 1.0, double(kMaxAutoHistogramBins)));
}

HistogramBinning integerBinning(std::int64_t first, std::int64_t last) {
    const std::int64_t span = last - first + 1; // values first..last
    const std::int64_t width = (span + kMaxAutoHistogramBins - 1) / kMaxAutoHistogramBins;
    HistogramBinning b;
    b.integerWidth = width;
    b.bins = static_cast<int>((span + width - 1) / width);
    b.lo = static_cast<double>(first);
    b.hi = static_cast<double>(first + b.bins * width);
    return b;
}

void validate(const HistogramSpec& spec) {
    if (spec.bins < 0 || spec.bins > kMaxHistogramBins)
        throw std::invalid_argument("histogram bins must be 0 (automatic) to " +
                                    std::to_string(kMaxHistogramBins) + ", not " +
                                    std::to_string(spec.bins));
    if (spec.range) {
        const auto [lo, hi] = *spec.range;
        if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo))
            throw std::invalid_argument("histogram range must be finite");
        if (lo > hi)
            throw std::invalid_argument("histogram range has low > high");
    }
}

// Per-thread counts: bin k at [2k] (all) and [2k + 1] (visible).
struct LocalCounts {
    std::vector<std::uint32_t> bins;
    std::uint64_t nan[2] = {0, 0};
    std::uint64_t outside[2] = {0, 0};
    explicit LocalCounts(int nBins) : bins(2 * static_cast<std::size_t>(nBins), 0) {}
};

// Bin of a value already known to lie in [lo, hi], decided against the edges.
struct EqualWidthBins {
    double lo, hi, scale;
    int bins;
    const double* edges;
    int operator()(double v) const {
        int k = static_cast<int>((v - lo) * scale);
        if (k >= bins)
            k = bins - 1;
        if (v < edges[k])
            --k;
        else if (k + 1 < bins && v >= edges[k + 1])
            ++k;
        return k;
    }
};

template <typename T, bool kMasked, bool kInteger>
void countRange(const T* values, const std::uint8_t* mask, std::size_t begin, std::size_t end,
                const HistogramBinning& binning, const EqualWidthBins& equal, LocalCounts& local) {
    std::uint32_t* counts = local.bins.data();
    const std::int64_t first = static_cast<std::int64_t>(binning.lo);
    const std::int64_t last = static_cast<std::int64_t>(binning.hi) - 1;
    const std::int64_t width = binning.integerWidth;
    for (std::size_t i = begin; i < end; ++i) {
        const unsigned m = kMasked ? (mask[i] != 0) : 0u;
        int k;
        if constexpr (kInteger && std::is_same_v<T, std::int32_t>) {
            const std::int64_t v = values[i];
            if (v < first || v > last) {
                ++local.outside[0];
                local.outside[1] += m;
                continue;
            }
            k = static_cast<int>(width == 1 ? v - first : (v - first) / width);
        } else if constexpr (kInteger) {
            // Integer bins applied to a float column (a binning reused across frames).
            const double v = static_cast<double>(values[i]);
            if (!(v >= binning.lo && v < binning.hi)) {
                const int nan = v != v;
                local.nan[0] += nan;
                local.nan[1] += nan & m;
                local.outside[0] += 1 - nan;
                local.outside[1] += (1 - nan) & m;
                continue;
            }
            k = std::min(binning.bins - 1,
                         static_cast<int>(std::floor((v - binning.lo) / double(width))));
        } else {
            const double v = static_cast<double>(values[i]);
            if (!(v >= equal.lo && v <= equal.hi)) {
                const int nan = v != v;
                local.nan[0] += nan;
                local.nan[1] += nan & m;
                local.outside[0] += 1 - nan;
                local.outside[1] += (1 - nan) & m;
                continue;
            }
            k = equal(v);
        }
        counts[2 * k] += 1;
        counts[2 * k + 1] += m;
    }
}

} // namespace

std::vector<double> HistogramBinning::edges() const {
    std::vector<double> e(static_cast<std::size_t>(bins) + 1);
    if (isInteger()) {
        for (int k = 0; k <= bins; ++k)
            e[k] = lo + static_cast<double>(k * integerWidth);
        return e;
    }
    const double step = (hi - lo) / bins;
    for (int k = 0; k < bins; ++k)
        e[k] = lo + k * step;
    e[bins] = hi;
    return e;
}

std::optional<int> HistogramBinning::binOf(double value) const {
    if (std::isnan(value))
        return std::nullopt;
    if (isInteger()) {
        if (value < lo || value >= hi)
            return std::nullopt;
        return static_cast<int>(std::floor((value - lo) / static_cast<double>(integerWidth)));
    }
    if (value < lo || value > hi)
        return std::nullopt;
    const std::vector<double> e = edges();
    return EqualWidthBins{lo, hi, bins / (hi - lo), bins, e.data()}(value);
}

std::uint64_t HistogramCounts::inRange() const {
    std::uint64_t sum = 0;
    for (std::uint64_t c : bins)
        sum += c;
    return sum;
}

std::uint64_t HistogramCounts::maxBin() const {
    return bins.empty() ? 0 : *std::max_element(bins.begin(), bins.end());
}

HistogramBinning chooseBinning(const ColumnView& column, const HistogramSpec& spec) {
    validate(spec);
    const bool integer = column.isInteger();

    if (integer && spec.bins == 0) {
        if (spec.range) {
            // Integer columns hold int32 values: a wider range adds only empty bins.
            constexpr double kMin = std::numeric_limits<std::int32_t>::min();
            constexpr double kMax = std::numeric_limits<std::int32_t>::max();
            const double first = std::clamp(std::ceil((*spec.range)[0]), kMin, kMax + 1.0);
            const double last = std::clamp(std::floor((*spec.range)[1]), kMin - 1.0, kMax);
            if (first <= last)
                return integerBinning(static_cast<std::int64_t>(first),
                                      static_cast<std::int64_t>(last));
            // No integer inside the range: one equal-width bin over it (below).
        } else {
            const auto range = finiteRange(column);
            return range ? integerBinning(static_cast<std::int64_t>((*range)[0]),
                                          static_cast<std::int64_t>((*range)[1]))
                         : integerBinning(0, 0);
        }
    }

    HistogramBinning b;
    if (spec.range) {
        b.lo = (*spec.range)[0];
        b.hi = (*spec.range)[1];
    } else if (const auto range = finiteRange(column)) {
        b.lo = (*range)[0];
        b.hi = (*range)[1] + (integer ? 1.0 : 0.0);
    } else {
        b.lo = b.hi = 0.0;
    }
    if (b.lo == b.hi) {
        b.lo -= 0.5;
        b.hi += 0.5;
    }
    if (spec.bins > 0)
        b.bins = spec.bins;
    else if (integer) // an integer range with no integer inside
        b.bins = 1;
    else
        b.bins = freedmanDiaconisBins(column, b.lo, b.hi);
    return b;
}

Histogram computeHistogram(const ColumnView& column, const HistogramBinning& binning,
                           const std::vector<std::uint8_t>* visibleMask) {
    assert(binning.bins >= 1 && binning.lo < binning.hi);
    assert(!visibleMask || visibleMask->size() == column.size);
    Histogram h;
    h.binning = binning;
    h.edges = binning.edges();
    h.hasVisible = visibleMask != nullptr;
    // Float columns are compared against edges rounded to the nearest float, as the values
    // were when read and as thresholds are (row_bits.hpp): a value written in the file as
    // exactly an edge, such as a radius of 0.005, falls in the bin that edge opens.
    std::vector<double> compareEdges = h.edges;
    if (!column.isInteger())
        for (double& e : compareEdges)
            e = static_cast<double>(detail::nearestFloatBound(e));
    const EqualWidthBins equal{compareEdges.front(), compareEdges.back(),
                               binning.bins / (binning.hi - binning.lo), binning.bins,
                               compareEdges.data()};
    const std::uint8_t* mask = visibleMask ? visibleMask->data() : nullptr;

    tbb::enumerable_thread_specific<LocalCounts> locals(LocalCounts(binning.bins));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, column.size, kGrainRows),
                      [&](const tbb::blocked_range<std::size_t>& rows) {
                          LocalCounts& local = locals.local();
                          auto run = [&]<typename T>(const T* values) {
                              const bool integer = binning.isInteger();
                              if (mask && integer)
                                  countRange<T, true, true>(values, mask, rows.begin(), rows.end(),
                                                            binning, equal, local);
                              else if (mask)
                                  countRange<T, true, false>(values, mask, rows.begin(), rows.end(),
                                                             binning, equal, local);
                              else if (integer)
                                  countRange<T, false, true>(values, mask, rows.begin(), rows.end(),
                                                             binning, equal, local);
                              else
                                  countRange<T, false, false>(values, mask, rows.begin(),
                                                              rows.end(), binning, equal, local);
                          };
                          if (column.isInteger())
                              run(column.ints);
                          else
                              run(column.floats);
                      });

    const auto nBins = static_cast<std::size_t>(binning.bins);
    h.all.bins.assign(nBins, 0);
    if (h.hasVisible)
        h.visible.bins.assign(nBins, 0);
    for (const LocalCounts& local : locals) {
        for (std::size_t k = 0; k < nBins; ++k) {
            h.all.bins[k] += local.bins[2 * k];
            if (h.hasVisible)
                h.visible.bins[k] += local.bins[2 * k + 1];
        }
        h.all.nan += local.nan[0];
        h.all.outside += local.outside[0];
        if (h.hasVisible) {
            h.visible.nan += local.nan[1];
            h.visible.outside += local.outside[1];
        }
    }
    return h;
}

std::optional<Histogram> computeHistogram(const Frame& frame, std::string_view variable,
                                          const HistogramSpec& spec,
                                          const std::vector<std::uint8_t>* visibleMask) {
    const auto column = findColumn(frame, variable);
    if (!column)
        return std::nullopt;
    return computeHistogram(*column, chooseBinning(*column, spec), visibleMask);
}

bool extremesStretchAxis(const Histogram& h, double share) {
    const auto& bins = h.all.bins;
    const std::uint64_t total = h.all.inRange();
    // All in one bar: one value (or values closer than a bar), which no middle view spreads.
    if (bins.size() < 2 || total < 20 || h.edges.size() != bins.size() + 1 ||
        h.all.maxBin() == total)
        return false;
    std::size_t left = 0, right = bins.size();
    for (std::uint64_t sum = 0; left < bins.size() && (sum + bins[left]) * 100 <= total;)
        sum += bins[left++];
    for (std::uint64_t sum = 0; right > left && (sum + bins[right - 1]) * 100 <= total;)
        sum += bins[--right];
    const double width = h.edges.back() - h.edges.front();
    const double outside = (h.edges[left] - h.edges.front()) + (h.edges.back() - h.edges[right]);
    return width > 0 && outside >= share * width;
}

std::vector<double> logCounts(const std::vector<std::uint64_t>& counts) {
    std::vector<double> out(counts.size());
    for (std::size_t k = 0; k < counts.size(); ++k)
        out[k] = std::log10(1.0 + static_cast<double>(counts[k]));
    return out;
}

} // namespace faultline::core
