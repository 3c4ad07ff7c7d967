#include "core/faults/metric_fields.hpp"

#include <array>
#include <limits>

namespace faultline::core {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double plane(const FaultFrameMetrics& m, double v) { return m.planeValid ? v : kNaN; }
double slip(const FaultFrameMetrics& m, double v) {
    return m.throwStatus == ThrowStatus::Ok ? v : kNaN;
}
double members(const FaultFrameMetrics& m, double v) { return m.count > 0 ? v : kNaN; }

const std::array<MetricField, 20> kFields{{
    {"count", "members present", "spheres", true,
     [](const FaultFrameMetrics& m) { return double(m.count); }},
    {"dip", "dip", "degrees", false, [](const FaultFrameMetrics& m) { return plane(m, m.dip); }},
    {"dip_direction", "dip direction", "degrees", false,
     [](const FaultFrameMetrics& m) { return plane(m, m.dipDirection); }},
    {"strike", "strike", "degrees", false,
     [](const FaultFrameMetrics& m) { return plane(m, m.strike); }},
    {"thickness", "thickness", "", false,
     [](const FaultFrameMetrics& m) { return plane(m, m.thickness); }},
    {"area", "area", "", false, [](const FaultFrameMetrics& m) { return plane(m, m.area); }},
    {"length", "length along strike", "", false,
     [](const FaultFrameMetrics& m) { return plane(m, m.length); }},
    {"height", "height down dip", "", false,
     [](const FaultFrameMetrics& m) { return plane(m, m.height); }},
    {"throw", "throw (vertical)", "", false,
     [](const FaultFrameMetrics& m) { return slip(m, m.throwVertical); }},
    {"net_slip", "net slip", "", false,
     [](const FaultFrameMetrics& m) { return slip(m, m.netSlip); }},
    {"dip_slip", "dip slip", "", false,
     [](const FaultFrameMetrics& m) { return slip(m, m.dipSlip); }},
    {"strike_slip", "strike slip", "", false,
     [](const FaultFrameMetrics& m) { return slip(m, m.strikeSlip); }},
    {"extent_x", "extent east-west", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.max[0] - m.min[0]); }},
    {"extent_y", "extent north-south", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.max[1] - m.min[1]); }},
    {"extent_z", "extent vertical", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.max[2] - m.min[2]); }},
    {"centroid_x", "centroid x (east)", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.centroid[0]); }},
    {"centroid_y", "centroid y (north)", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.centroid[1]); }},
    {"centroid_z", "centroid z (up)", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.centroid[2]); }},
    {"broken", "members with broken bonds", "spheres", true,
     [](const FaultFrameMetrics& m) { return double(m.broken); }},
    {"mean_radius", "mean radius", "", false,
     [](const FaultFrameMetrics& m) { return members(m, m.meanRadius); }},
}};

} // namespace

std::span<const MetricField> metricFields() { return kFields; }

const MetricField* findMetricField(std::string_view key) {
    for (const MetricField& f : kFields)
        if (f.key == key)
            return &f;
    return nullptr;
}

} // namespace faultline::core
