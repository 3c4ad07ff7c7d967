#include "core/session/session_state.hpp"
#include "core/util/enum_names.hpp"

#include "core/color/colormap.hpp"
#include "core/surface/surface_params.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace faultline::core {

namespace {
constexpr EnumName<ColorDifference::Mode> kDifferenceModes[] = {
    {ColorDifference::Mode::None, "none"},
    {ColorDifference::Mode::Change, "change"},
    {ColorDifference::Mode::Displacement, "displacement"}};
constexpr EnumName<FaultFilter::Mode> kFaultFilterModes[] = {
    {FaultFilter::Mode::All, "all"},
    {FaultFilter::Mode::Labelled, "labelled"},
    {FaultFilter::Mode::Only, "only"}};
} // namespace

std::string_view faultFilterModeName(FaultFilter::Mode mode) {
    return nameIn(kFaultFilterModes, mode, "all");
}
std::optional<FaultFilter::Mode> parseFaultFilterMode(std::string_view name) {
    return valueIn(kFaultFilterModes, name);
}
std::string faultFilterModeNames() { return namesIn(kFaultFilterModes, ", ", " or "); }

std::string_view differenceModeName(ColorDifference::Mode mode) {
    return nameIn(kDifferenceModes, mode, "none");
}

RangeMode effectiveRangeMode(const ViewState& view) {
    if (view.rangeMode == RangeMode::Fixed || view.difference.mode == ColorDifference::Mode::None)
        return view.rangeMode;
    return RangeMode::AllFrames;
}

std::size_t referenceFrame(const ViewState& view, std::size_t shown, std::size_t count) {
    const FrameBinding& ref = view.difference.reference;
    const long long f = ref.relative ? static_cast<long long>(shown) + ref.value : ref.value;
    return static_cast<std::size_t>(
        std::clamp(f, 0LL, std::max(1LL, static_cast<long long>(count)) - 1));
}

std::string colorTitle(const ViewState& view, std::size_t referenceFrame) {
    const std::string since = " since frame " + std::to_string(referenceFrame);
    switch (view.difference.mode) {
    case ColorDifference::Mode::Change:
        return view.colorVariable.empty() ? std::string() : view.colorVariable + " change" + since;
    case ColorDifference::Mode::Displacement:
        return "displacement" + since;
    case ColorDifference::Mode::None:
        break;
    }
    return view.colorVariable;
}

std::optional<ColorDifference::Mode> parseDifferenceMode(std::string_view name) {
    return valueIn(kDifferenceModes, name);
}

namespace {
template <typename Vec, typename Key> auto findIn(Vec& items, Key key, std::string_view name) {
    auto it =
        std::find_if(items.begin(), items.end(), [&](const auto& e) { return e.*key == name; });
    return it == items.end() ? nullptr : &*it;
}
} // namespace

ViewState* SessionState::view(std::string_view name) {
    return findIn(views, &ViewState::name, name);
}
const ViewState* SessionState::view(std::string_view name) const {
    return findIn(views, &ViewState::name, name);
}
CuttingBox* SessionState::box(std::string_view name) {
    return findIn(boxes, &CuttingBox::name, name);
}
const CuttingBox* SessionState::box(std::string_view name) const {
    return findIn(boxes, &CuttingBox::name, name);
}
const VariableThreshold* SessionState::threshold(std::string_view variable) const {
    return findIn(thresholds, &VariableThreshold::variable, variable);
}
const SurfaceSettings* SessionState::surface(std::string_view fault) const {
    return findIn(surfaces, &SurfaceSettings::fault, fault);
}
std::vector<std::string> SessionState::shownSurfaces() const {
    std::vector<std::string> out;
    for (const auto& st : surfaces)
        if (st.visible && hasSurfaceSource(st.fault))
            out.push_back(st.fault);
    return out;
}
VariableThreshold* SessionState::threshold(std::string_view variable) {
    return findIn(thresholds, &VariableThreshold::variable, variable);
}
Fault* SessionState::fault(std::string_view name) { return findIn(faults, &Fault::name, name); }
const Fault* SessionState::fault(std::string_view name) const {
    return findIn(faults, &Fault::name, name);
}
SurfaceSettings* SessionState::surface(std::string_view fault) {
    return findIn(surfaces, &SurfaceSettings::fault, fault);
}

} // namespace faultline::core
