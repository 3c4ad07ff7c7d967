// Tick values and labels for a colour-bar legend: "nice" round steps (1, 2, 2.5, 5 x 10^k) inside
// the range, labelled with just enough decimals to tell neighbouring ticks apart.
#pragma once

#include "core/color/colormap.hpp"

#include <string>
#include <vector>

namespace faultline::core {

struct LegendTick {
    double value = 0.0;
    double t = 0.0; // position along the bar, 0 at range.low, 1 at range.high
    std::string label;
};

// Between 2 and maxTicks ticks inside [range.low, range.high] (both ends included when they
// fall on a step). An empty range gives its two ends.
// integerSteps: only whole-number steps (for integer variables such as broken bonds).
std::vector<LegendTick> legendTicks(ValueRange range, int maxTicks = 6, bool integerSteps = false);

// The smallest round step (1, 2, 2.5 or 5 times a power of ten) that puts at most maxTicks
// ticks inside the range; 1 for an empty range.
double niceStep(ValueRange range, int maxTicks, bool integerSteps = false);

// A tick label for v on a grid of `step`: "0.25", "-3", "1.5e+06".
std::string formatTick(double v, double step);

} // namespace faultline::core
