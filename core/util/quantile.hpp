// Quantiles of a sample by selection, without sorting it.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace faultline::core {

// Quantile p (0..1) of the values in sorted order by linear interpolation (numpy's default,
// "type 7"), via selection; `values` is reordered and must not be empty.
inline double quantile(std::vector<float>& values, double p) {
    assert(!values.empty());
    const double h = static_cast<double>(values.size() - 1) * p;
    const auto k = static_cast<std::size_t>(std::floor(h));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    const double below = values[k];
    if (k + 1 >= values.size())
        return below;
    const double above =
        *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(k) + 1, values.end());
    return below + (h - static_cast<double>(k)) * (above - below);
}

// quantile(values, low) and quantile(values, high), the same values, for low < high. Above 65,536
// values by bins rather than selection: one pass for the range, one counting the values into
// 4,096 bins of it (monotonic: a larger value never falls in a lower bin), then each order
// statistic wanted is picked from its own bin's values alone. A colour range's percentiles of a
// million spheres took 10 ms by selection, on the UI thread at each new frame. `values` may be
// reordered; it must not be empty, nor hold NaN.
inline std::pair<double, double> quantilePair(std::vector<float>& values, double low, double high) {
    assert(!values.empty() && low < high);
    const std::size_t n = values.size();
    if (n <= 65536) {
        const double lo = quantile(values, low);
        return {lo, quantile(values, high)};
    }
    const auto [minIt, maxIt] = std::minmax_element(values.begin(), values.end());
    const float vmin = *minIt, vmax = *maxIt;
    if (!(vmax > vmin) || !std::isfinite(double(vmax) - double(vmin)))
        return {quantile(values, low), quantile(values, high)}; // one value, or infinities
    constexpr std::size_t kBins = 4096;
    const double scale = double(kBins) / (double(vmax) - double(vmin));
    auto binOf = [&](float v) {
        const double b = (double(v) - double(vmin)) * scale; // >= 0, monotonic in v
        return b >= double(kBins - 1) ? kBins - 1 : static_cast<std::size_t>(b);
    };
    std::vector<std::size_t> count(kBins, 0);
    for (float v : values)
        ++count[binOf(v)];
    // The order statistics type 7 reads: k and k + 1 for each quantile.
    auto rankOf = [&](double p) {
        return static_cast<std::size_t>(std::floor(static_cast<double>(n - 1) * p));
    };
    const std::size_t ranks[4] = {rankOf(low), std::min(rankOf(low) + 1, n - 1), rankOf(high),
                                  std::min(rankOf(high) + 1, n - 1)};
    std::size_t binOfRank[4], before[4];
    for (int r = 0; r < 4; ++r) {
        std::size_t cum = 0, b = 0;
        while (cum + count[b] <= ranks[r])
            cum += count[b++];
        binOfRank[r] = b;
        before[r] = cum;
    }
    // The values of the bins wanted (at most four: ranks in one bin share its list), in no order:
    // each rank is selected within its bin below.
    std::vector<float> inBin[4];
    for (float v : values) {
        const std::size_t b = binOf(v);
        for (int r = 0; r < 4; ++r)
            if (b == binOfRank[r]) {
                inBin[r].push_back(v);
                break; // the first rank of that bin holds the list
            }
    }
    auto at = [&](int r) {
        int owner = 0;
        while (binOfRank[owner] != binOfRank[r])
            ++owner;
        std::vector<float>& bin = inBin[owner];
        const std::size_t k = ranks[r] - before[r];
        std::nth_element(bin.begin(), bin.begin() + static_cast<std::ptrdiff_t>(k), bin.end());
        return static_cast<double>(bin[k]);
    };
    auto interpolate = [&](double p, int r) {
        const double h = static_cast<double>(n - 1) * p;
        const double below = at(r);
        if (ranks[r] + 1 >= n)
            return below;
        return below + (h - std::floor(h)) * (at(r + 1) - below);
    };
    const double lo = interpolate(low, 0);
    return {lo, interpolate(high, 2)};
}

} // namespace faultline::core
