// Histogram: counts of one per-sphere variable in bins, for all spheres and the visible ones in
// one parallel pass. Drives the Histograms panel and the journal's `expect histogram`.
//
// Binning (chooseBinning):
//   - Equal-width bins over [lo, hi): bin k is [edge k, edge k+1), the last bin also holds hi,
//     edges[k] = lo + k * (hi - lo) / bins (edges[bins] = hi exactly), as numpy.histogram.
//     A value's bin is decided against these edges, so a value on an edge goes right.
//   - Integer bins: for an integer column with automatic bins, one bin per integer value over
//     [min, max + 1). When that is more than 256 values, each bin holds `integerWidth`
//     consecutive integers (the smallest width giving <= 256 bins) and the last bin ends at
//     lo + bins * integerWidth, past max; bins stay aligned to whole values.
//   - Automatic range: the column's finite min/max; [min, max + 1] for integer columns. A range
//     of zero width (constant column, empty or all-NaN frame) is widened to [v-0.5, v+0.5].
//   - Automatic count of equal-width bins (float columns): Freedman-Diaconis, bin width
//     2 IQR / n^(1/3) over the finite values of the whole column (exact quartiles, linear
//     interpolation as numpy's default), capped at 256, at least 1. When the IQR is 0 (FD
//     undefined) Sturges' ceil(log2 n) + 1 is used instead. FD needs quartiles (a selection
//     over a copy of the column, see the bench for its cost): choose the binning once per
//     (frame, variable, spec) and reuse it when only the visible mask changes.
// Counting (computeHistogram): NaN values go to `nan`; finite or infinite values outside the
// range go to `outside`; a row is visible when mask[row] != 0.
#pragma once

#include "core/model/frame.hpp"
#include "core/selection/column_view.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace faultline::core {

inline constexpr int kMaxAutoHistogramBins = 256;
inline constexpr int kMaxHistogramBins = 65536; // explicit requests beyond this are errors

struct HistogramSpec {
    int bins = 0;                               // 0: automatic
    std::optional<std::array<double, 2>> range; // nullopt: automatic
};

struct HistogramBinning {
    double lo = 0.0;
    double hi = 1.0;
    int bins = 1;
    std::int64_t integerWidth = 0; // > 0: integer bins, bin k = [lo + k w, lo + (k+1) w)

    bool isInteger() const { return integerWidth > 0; }
    std::vector<double> edges() const; // bins + 1 values
    // The bin of one value, or nullopt when NaN or outside (the per-value specification).
    std::optional<int> binOf(double value) const;
    bool operator==(const HistogramBinning&) const = default;
};

struct HistogramCounts {
    std::vector<std::uint64_t> bins;
    std::uint64_t nan = 0;     // NaN values
    std::uint64_t outside = 0; // non-NaN values outside the range
    std::uint64_t inRange() const;
    std::uint64_t maxBin() const; // 0 when there are no bins or all are empty
};

struct Histogram {
    HistogramBinning binning;
    std::vector<double> edges; // binning.edges()
    HistogramCounts all;
    HistogramCounts visible; // filled only when hasVisible
    bool hasVisible = false;
};

// Resolves automatic bins and range. Throws std::invalid_argument for bins < 0 or above
// kMaxHistogramBins, or a range with a non-finite bound or lo > hi.
HistogramBinning chooseBinning(const ColumnView& column, const HistogramSpec& spec = {});

// Counts all rows and, when visibleMask is given (column.size bytes), the visible ones.
Histogram computeHistogram(const ColumnView& column, const HistogramBinning& binning,
                           const std::vector<std::uint8_t>* visibleMask = nullptr);

// Both steps for a variable of a frame; nullopt when the frame has no such variable.
std::optional<Histogram> computeHistogram(const Frame& frame, std::string_view variable,
                                          const HistogramSpec& spec = {},
                                          const std::vector<std::uint8_t>* visibleMask = nullptr);

// For a log-scale plot: log10(1 + count) per bin (empty bins stay at 0, one sphere is 0.30).
std::vector<double> logCounts(const std::vector<std::uint64_t>& counts);

// Whether the values outside their 1st to 99th percentile stretch over `share` of the plot's
// axis, told from whole bins at either end holding at most 1 % of the values each (a few
// extreme values, such as grains thrown out of a model, set the range: a view of the middle 98 %
// shows the rest better). False for fewer than 20 values or 2 bins, and when all are in one bar.
bool extremesStretchAxis(const Histogram& h, double share = 0.8);

} // namespace faultline::core
