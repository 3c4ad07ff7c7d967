#include "core/session/items/threshold_codec.hpp"

namespace faultline::core::items {

namespace {
// Each field once: its JSON and how it is read.
const Field<VariableThreshold> kFields[] = {
    {"variable", [](const VariableThreshold& t) { return Json(t.variable); },
     [](VariableThreshold& t, const ItemReader& f, const char* n) { f.read(n, t.variable); }},
    {"low", [](const VariableThreshold& t) { return Json(t.low); },
     [](VariableThreshold& t, const ItemReader& f, const char* n) { f.read(n, t.low); }},
    {"high", [](const VariableThreshold& t) { return Json(t.high); },
     [](VariableThreshold& t, const ItemReader& f, const char* n) { f.read(n, t.high); }},
    {"enabled", [](const VariableThreshold& t) { return Json(t.enabled); },
     [](VariableThreshold& t, const ItemReader& f, const char* n) { f.read(n, t.enabled); }},
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
