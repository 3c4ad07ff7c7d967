#include "core/session/items/strain_codec.hpp"

#include <cctype>
#include <cmath>

namespace faultline::core::items {

Json toJson(const StrainSpec& s) {
    Json j = Json::object();
    j[s.relative ? "since_offset" : "since_frame"] = s.reference;
    if (s.cutoff > 0)
        j["cutoff"] = s.cutoff;
    if (!s.prefix.empty())
        j["prefix"] = s.prefix;
    return j;
}

namespace {

long long wholeNumber(const ItemReader& f, const char* field) {
    const Json& v = f.get(field);
    if (!v.is_number() || (v.is_number_float() && v.get<double>() != std::floor(v.get<double>())))
        f.fail(field, "must be a whole number", &v);
    // Frame numbers and offsets: anything past a billion frames is no frame (and a cast of a
    // larger double would be undefined).
    const double d = v.get<double>();
    if (!(std::fabs(d) < 1e9))
        f.fail(field, "must be a whole number of frames", &v);
    return static_cast<long long>(d);
}

} // namespace

void patch(StrainSpec& s, const ItemReader& f) {
    if (f.has("since_frame") && f.has("since_offset"))
        f.fail("since_offset", "goes with no \"since_frame\": give one of them");
    if (f.has("since_frame")) {
        s.relative = false;
        s.reference = wholeNumber(f, "since_frame");
    }
    if (f.has("since_offset")) {
        s.relative = true;
        s.reference = wholeNumber(f, "since_offset");
    }
    if (f.has("cutoff")) {
        const Json& v = f.get("cutoff");
        if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
            f.fail("cutoff", "must be a number > 0", &v);
        s.cutoff = v.get<double>();
    }
    f.read("prefix", s.prefix);
}

void validate(const StrainSpec& s) {
    if (!s.relative && s.reference < 0)
        breaks("since_frame", "must be >= 0");
    if (s.relative && s.reference == 0)
        breaks("since_offset", "must not be 0 (a frame against itself has no strain)");
    if (!(s.cutoff >= 0) || !std::isfinite(s.cutoff))
        breaks("cutoff", "must be a number > 0");
    for (char c : s.prefix)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.')
            breaks("prefix", "may hold only letters, digits, '_', '-' and '.'");
}

} // namespace faultline::core::items
