#include "core/model/packing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace faultline::core {

int flatAxis(const Frame& f) {
    if (f.size() < 2)
        return -1;
    for (int a = 0; a < 3; ++a)
        if (f.centreMin()[a] == f.centreMax()[a])
            return a;
    return -1;
}

std::pair<double, int> centreBounds(const Frame& f) {
    const int flat = flatAxis(f);
    double volume = 1;
    int dims = 0;
    for (int a = 0; a < 3; ++a) {
        const double l = double(f.centreMax()[a]) - f.centreMin()[a];
        if (a == flat || !(l > 0))
            continue;
        volume *= l;
        ++dims;
    }
    return {volume, dims};
}

double packingSpacing(const Frame& f) {
    const std::size_t n = f.size();
    const auto [volume, dims] = centreBounds(f);
    if (n == 0 || dims == 0 || !std::isfinite(volume))
        return 1.0;
    return dims == 3   ? std::cbrt(0.64 * volume * 6.0 / (M_PI * double(n)))
           : dims == 2 ? std::sqrt(0.84 * volume * 4.0 / (M_PI * double(n)))
                       : volume / double(n);
}

double medianRadius(const Frame& f, std::size_t samples) {
    const std::size_t n = f.size();
    if (n == 0 || f.radiusIsDefault)
        return std::numeric_limits<double>::quiet_NaN();
    const std::size_t step = std::max<std::size_t>(1, n / std::max<std::size_t>(1, samples));
    std::vector<float> sample;
    sample.reserve(n / step + 1);
    for (std::size_t i = 0; i < n; i += step)
        sample.push_back(f.radius[i]);
    std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
    const double r = sample[sample.size() / 2];
    return r > 0 && std::isfinite(r) ? r : std::numeric_limits<double>::quiet_NaN();
}

double radiiOverSpacing(const Frame& f) {
    // A few spheres fill no bounds: their spacing says nothing (two spheres side by side read
    // as overlapping four times over).
    if (f.size() < kMinSpheresForSpacing || centreBounds(f).second == 0)
        return std::numeric_limits<double>::quiet_NaN();
    return 2.0 * medianRadius(f, 1024) / packingSpacing(f);
}

std::string radiiUnitNote(const Frame& f) {
    const double ratio = radiiOverSpacing(f);
    if (!(ratio > kRadiiFarOverSpacing) && !(ratio < kRadiiTinyOverSpacing))
        return {}; // NaN too
    const double spacing = packingSpacing(f);
    char text[240];
    if (ratio > kRadiiFarOverSpacing)
        std::snprintf(text, sizeof text,
                      "the median diameter is %.4g, about %.0f times the spacing of the centres "
                      "(%.4g): are the radii in another unit?",
                      ratio * spacing, ratio, spacing);
    else
        std::snprintf(text, sizeof text,
                      "the median diameter is %.4g, about 1/%.0f of the spacing of the centres "
                      "(%.4g): are the radii in another unit?",
                      ratio * spacing, 1.0 / ratio, spacing);
    return text;
}

double radiusDrawScale(const Frame& f) {
    const double ratio = radiiOverSpacing(f);
    return ratio > kRadiiFarOverSpacing && std::isfinite(ratio) ? 1.0 / ratio : 1.0;
}

} // namespace faultline::core
