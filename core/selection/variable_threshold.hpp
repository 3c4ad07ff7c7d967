// VariableThreshold: keeps spheres whose value of one variable lies in [low, high] (inclusive).
// At most one per variable; NaN values never pass.
#pragma once

#include <string>

namespace faultline::core {

struct VariableThreshold {
    std::string variable;
    double low = -1e30;
    double high = 1e30;
    bool enabled = true;

    bool passes(double v) const { return v >= low && v <= high; }
    bool operator==(const VariableThreshold&) const = default;
};

} // namespace faultline::core
