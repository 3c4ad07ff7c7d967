#include "ui/context/frame_columns.hpp"

#include "core/model/packing.hpp"
#include "core/selection/column_view.hpp"
#include "core/view/framing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace faultline::ui {

std::vector<std::string> variableNames(const core::Frame& frame) {
    return core::variableNamesOf(frame);
}

std::optional<VariableInfo> variableInfo(const core::Frame& frame, const std::string& name) {
    if (const core::AttributeColumn* c = frame.attribute(name))
        return VariableInfo{c->min, c->max, c->isInteger()};
    if (const auto r = core::variableRange(frame, name)) // x, y, z, radius
        return VariableInfo{r->low, r->high, false};
    return std::nullopt;
}

const ColumnCatalog::Entries& ColumnCatalog::of(const std::shared_ptr<const core::Frame>& frame) {
    static const Entries kNone;
    if (!frame)
        return kNone;
    for (auto& [f, entries] : m_recent)
        if (f == frame)
            return entries;
    Entries entries;
    for (const std::string& name : variableNames(*frame))
        if (auto info = variableInfo(*frame, name))
            entries.emplace_back(name, *info);
    if (m_recent.size() >= 3)
        m_recent.erase(m_recent.begin());
    m_recent.emplace_back(frame, std::move(entries));
    return m_recent.back().second;
}

std::optional<VariableInfo> ColumnCatalog::info(const std::shared_ptr<const core::Frame>& frame,
                                                const std::string& name) {
    for (const auto& [n, info] : of(frame))
        if (n == name)
            return info;
    return std::nullopt;
}

namespace {

// As drawn: radii far larger than the centres' spacing are drawn scaled down (the renderer's
// core::radiusDrawScale), and the views frame what they draw.
double largestRadius(const core::Frame& frame) {
    double r = 0;
    for (float f : frame.radius)
        if (std::isfinite(f))
            r = std::max<double>(r, f);
    return r * core::radiusDrawScale(frame);
}

} // namespace

ModelBounds modelBounds(const core::Frame& frame) {
    ModelBounds b;
    if (frame.size() == 0)
        return b;
    const double r = largestRadius(frame);
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = frame.centreMin()[a] - r;
        b.hi[a] = frame.centreMax()[a] + r;
    }
    return b;
}

ModelBounds framedBounds(const core::Frame& frame) {
    ModelBounds b;
    if (frame.size() == 0)
        return b;
    const double r = largestRadius(frame);
    const core::Framing f = core::framingBounds(frame);
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = f.lo[a] - r;
        b.hi[a] = f.hi[a] + r;
    }
    return b;
}

ModelBounds visibleBounds(const core::Frame& frame, const std::vector<std::uint8_t>& mask) {
    ModelBounds b;
    bool any = false;
    double r = 0;
    for (std::size_t i = 0; i < frame.size() && i < mask.size(); ++i) {
        if (!mask[i])
            continue;
        const double p[3] = {frame.x[i], frame.y[i], frame.z[i]};
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = any ? std::min(b.lo[a], p[a]) : p[a];
            b.hi[a] = any ? std::max(b.hi[a], p[a]) : p[a];
        }
        if (std::isfinite(frame.radius[i]))
            r = std::max<double>(r, frame.radius[i]);
        any = true;
    }
    if (!any)
        return modelBounds(frame);
    r *= core::radiusDrawScale(frame);
    for (int a = 0; a < 3; ++a)
        b.lo[a] -= r, b.hi[a] += r;
    return b;
}

std::string bytesText(std::size_t bytes) {
    char buf[32];
    if (bytes >= (std::size_t(1) << 30))
        std::snprintf(buf, sizeof buf, "%.2f GB", bytes / double(std::size_t(1) << 30));
    else if (bytes >= (std::size_t(1) << 20))
        std::snprintf(buf, sizeof buf, "%.1f MB", bytes / double(std::size_t(1) << 20));
    else
        std::snprintf(buf, sizeof buf, "%.0f KB", bytes / 1024.0);
    return buf;
}

std::string numberText(double v) {
    if (!std::isfinite(v))
        return v > 0 ? "inf" : v < 0 ? "-inf" : "nan";
    if (std::fabs(v) >= 1e30)
        return v > 0 ? "max" : "min";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

} // namespace faultline::ui
