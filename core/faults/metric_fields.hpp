// The per-frame fault metrics by name, as plots and tables pick them: one number per metric
// (NaN where it is undefined), with a label and unit, in a stable order.
#pragma once

#include "core/faults/metrics.hpp"

#include <span>
#include <string_view>

namespace faultline::core {

struct MetricField {
    std::string_view key;   // the CSV column name where there is one ("dip", "extent_x")
    std::string_view label; // for people ("dip direction")
    std::string_view unit;  // "degrees", "spheres", "" (model length units)
    bool integer = false;   // whole numbers only (counts)
    double (*value)(const FaultFrameMetrics&);
};

// count, dip, dip_direction, strike, thickness, area, throw, net_slip, dip_slip, strike_slip,
// extent_x, extent_y, extent_z, centroid_x, centroid_y, centroid_z, broken, mean_radius.
// Plane quantities are NaN without a valid plane; throw quantities NaN unless the throw status
// is ok; extents and centroid NaN without members.
std::span<const MetricField> metricFields();
// The field with this key, or null.
const MetricField* findMetricField(std::string_view key);

} // namespace faultline::core
