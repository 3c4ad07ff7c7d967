#include "core/session/session_state.hpp"

#include <algorithm>

namespace faultline::core {

namespace {
template <typename Vec, typename Key> auto findIn(Vec& items, Key key, std::string_view name) {
    auto it = std::find_if(items.begin(), items.end(), [&](const auto& e) { return e.*key == name; });
    return it == items.end() ? nullptr : &*it;
}
} // namespace

ViewState* SessionState::view(std::string_view name) { return findIn(views, &ViewState::name, name); }
const ViewState* SessionState::view(std::string_view name) const {
    return findIn(views, &ViewState::name, name);
}
CuttingBox* SessionState::box(std::string_view name) { return findIn(boxes, &CuttingBox::name, name); }
const CuttingBox* SessionState::box(std::string_view name) const {
    return findIn(boxes, &CuttingBox::name, name);
}
const VariableThreshold* SessionState::threshold(std::string_view variable) const {
    return findIn(thresholds, &VariableThreshold::variable, variable);
}
const SurfaceSettings* SessionState::surface(std::string_view fault) const {
    return findIn(surfaces, &SurfaceSettings::fault, fault);
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
