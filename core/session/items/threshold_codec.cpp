#include "core/session/items/threshold_codec.hpp"

namespace faultline::core::items {

namespace {
// Each field once: its JSON and how it is read.
using T = VariableThreshold;
const Field<T> kFields[] = {
    member<T, &T::variable>("variable"),
    member<T, &T::low>("low"),
    member<T, &T::high>("high"),
    member<T, &T::enabled>("enabled"),
};
} // namespace

Json toJson(const VariableThreshold& t) { return fieldsToJson(t, kFields); }

void patch(VariableThreshold& t, const ItemReader& f) { patchFields(t, f, kFields); }

std::vector<std::string> thresholdFieldNames() { return fieldNames(kFields); }

void validate(const VariableThreshold& t) {
    if (t.variable.empty())
        breaks("variable", "must not be empty");
    if (!(t.low <= t.high))
        breaks("low", "must not exceed high");
}

} // namespace faultline::core::items
