#include "core/color/legend_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace faultline::core {

double niceStep(ValueRange range, int maxTicks, bool integerSteps) {
    maxTicks = std::max(maxTicks, 2);
    const double span = range.high - range.low;
    if (!(span > 0.0) || !std::isfinite(span))
        return 1.0;
    // The smallest round step giving at most maxTicks ticks inside the range.
    double magnitude = std::pow(10.0, std::floor(std::log10(span / maxTicks)));
    for (int guard = 0; guard < 40; ++guard, magnitude *= 10.0) {
        for (double m : {1.0, 2.0, 2.5, 5.0}) {
            const double step = m * magnitude;
            if (integerSteps && (step < 1.0 || step != std::floor(step)))
                continue;
            const double eps = step * 1e-6;
            const double count =
                std::floor((range.high + eps) / step) - std::ceil((range.low - eps) / step) + 1.0;
            if (count <= maxTicks)
                return step;
        }
    }
    return span;
}

std::string formatTick(double v, double step) {
    char buf[64];
    const double mag = std::max(std::abs(v), std::abs(step));
    if (std::abs(v) < step * 1e-9)
        v = 0.0; // no "-0" or "1e-17" for a tick at zero
    if (mag >= 1e5 || (step < 1e-4 && mag < 1e-3)) {
        std::snprintf(buf, sizeof buf, "%.3g", v);
        return buf;
    }
    // Enough decimals for the step (2.5 needs one more than 2).
    int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    const double scaled = step * std::pow(10.0, decimals);
    if (std::abs(scaled - std::round(scaled)) > 1e-6)
        ++decimals;
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 10), v);
    return buf;
}

std::vector<LegendTick> legendTicks(ValueRange range, int maxTicks, bool integerSteps) {
    std::vector<LegendTick> ticks;
    const double span = range.high - range.low;
    if (!(span > 0.0) || !std::isfinite(span)) {
        ticks.push_back({range.low, 0.0, formatTick(range.low, 1.0)});
        ticks.push_back({range.high, 1.0, formatTick(range.high, 1.0)});
        return ticks;
    }
    const double step = niceStep(range, maxTicks, integerSteps);
    const double eps = step * 1e-6;
    const double first = std::ceil((range.low - eps) / step);
    for (double k = first;; k += 1.0) {
        const double v = k * step;
        if (v > range.high + eps)
            break;
        ticks.push_back({v, (v - range.low) / span, formatTick(v, step)});
    }
    if (ticks.size() < 2) { // a range narrower than one step: label its ends
        ticks.clear();
        const double fine = span;
        ticks.push_back({range.low, 0.0, formatTick(range.low, fine / 10)});
        ticks.push_back({range.high, 1.0, formatTick(range.high, fine / 10)});
    }
    return ticks;
}

} // namespace faultline::core
