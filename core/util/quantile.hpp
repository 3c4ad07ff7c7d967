// Quantiles of a sample by selection, without sorting it.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
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

} // namespace faultline::core
