#include "core/session/items/threshold_codec.hpp"

namespace faultline::core::items {

Json toJson(const VariableThreshold& t) {
    return {{"variable", t.variable}, {"low", t.low}, {"high", t.high}, {"enabled", t.enabled}};
}

void patch(VariableThreshold& t, const ItemReader& f) {
    f.read("variable", t.variable);
    f.read("low", t.low);
    f.read("high", t.high);
    f.read("enabled", t.enabled);
}

void validate(const VariableThreshold& t) {
    if (t.variable.empty())
        breaks("variable", "must not be empty");
    if (!(t.low <= t.high))
        breaks("low", "must not exceed high");
}

} // namespace faultline::core::items
