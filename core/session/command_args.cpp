#include "core/session/command_args.hpp"

#include <algorithm>

#include <cmath>

namespace faultline::core::args {

namespace {
std::string opOf(const Json& cmd) {
    auto it = cmd.find("op");
    return it != cmd.end() && it->is_string() ? it->get<std::string>() : std::string("command");
}
[[noreturn]] void fail(const Json& cmd, const char* field, const std::string& what) {
    throw CommandError(opOf(cmd) + ": \"" + field + "\" " + what);
}
double toNumber(const Json& cmd, const char* field, const Json& v) {
    if (!v.is_number())
        fail(cmd, field, "must be a number, found " + v.dump());
    const double d = v.get<double>();
    if (std::isnan(d))
        fail(cmd, field, "must be a number, found NaN");
    return d;
}
} // namespace

const Json& require(const Json& cmd, const char* field) {
    auto it = cmd.find(field);
    if (it == cmd.end())
        fail(cmd, field, "is missing");
    return *it;
}

std::string string(const Json& cmd, const char* field) {
    const Json& v = require(cmd, field);
    if (!v.is_string())
        fail(cmd, field, "must be a string, found " + v.dump());
    return v.get<std::string>();
}

std::optional<std::string> optionalString(const Json& cmd, const char* field) {
    if (!cmd.contains(field))
        return std::nullopt;
    return string(cmd, field);
}

double number(const Json& cmd, const char* field) {
    return toNumber(cmd, field, require(cmd, field));
}

std::optional<double> optionalNumber(const Json& cmd, const char* field) {
    if (!cmd.contains(field))
        return std::nullopt;
    return number(cmd, field);
}

long long integer(const Json& cmd, const char* field) {
    const Json& v = require(cmd, field);
    if (v.is_number_integer())
        return v.get<long long>();
    const double d = toNumber(cmd, field, v);
    if (d != std::trunc(d) || std::fabs(d) > 9e15)
        fail(cmd, field, "must be a whole number, found " + v.dump());
    return static_cast<long long>(d);
}

std::optional<long long> optionalInteger(const Json& cmd, const char* field) {
    if (!cmd.contains(field))
        return std::nullopt;
    return integer(cmd, field);
}

std::optional<bool> optionalBool(const Json& cmd, const char* field) {
    if (!cmd.contains(field))
        return std::nullopt;
    const Json& v = cmd.at(field);
    if (!v.is_boolean())
        fail(cmd, field, "must be true or false, found " + v.dump());
    return v.get<bool>();
}

std::array<double, 3> vec3(const Json& cmd, const char* field) {
    const Json& v = require(cmd, field);
    if (!v.is_array() || v.size() != 3)
        fail(cmd, field, "must be an array of 3 numbers, found " + v.dump());
    std::array<double, 3> out{};
    for (std::size_t k = 0; k < 3; ++k)
        out[k] = toNumber(cmd, field, v[k]);
    return out;
}

std::optional<std::array<double, 3>> optionalVec3(const Json& cmd, const char* field) {
    if (!cmd.contains(field))
        return std::nullopt;
    return vec3(cmd, field);
}

std::vector<std::int64_t> ids(const Json& cmd, const char* field) {
    const Json& v = require(cmd, field);
    if (!v.is_array())
        fail(cmd, field, std::string("must be an array of particle ids, found ") + v.type_name());
    std::vector<std::int64_t> out;
    out.reserve(v.size());
    for (const Json& e : v) {
        if (!e.is_number_integer())
            fail(cmd, field, "must hold whole numbers, found " + e.dump());
        out.push_back(e.get<std::int64_t>());
    }
    return out;
}

std::vector<std::string> strings(const Json& cmd, const char* field) {
    const Json& v = require(cmd, field);
    if (!v.is_array())
        fail(cmd, field, "must be an array of strings, found " + v.dump());
    std::vector<std::string> out;
    for (const Json& e : v) {
        if (!e.is_string())
            fail(cmd, field, "must hold strings, found " + e.dump());
        out.push_back(e.get<std::string>());
    }
    return out;
}

void onlyFields(const Json& cmd, std::initializer_list<const char*> keys,
                const std::vector<std::string>& itemFields) {
    for (auto it = cmd.begin(); it != cmd.end(); ++it) {
        if (it.key() == "op")
            continue;
        bool ok = std::find(itemFields.begin(), itemFields.end(), it.key()) != itemFields.end();
        for (const char* a : keys)
            ok |= it.key() == a;
        if (!ok) {
            std::string list; // the item's fields, then the command's own
            for (const std::string& a : itemFields)
                list += std::string(list.empty() ? "" : ", ") + a;
            for (const char* a : keys)
                list += std::string(list.empty() ? "" : ", ") + a;
            throw CommandError(opOf(cmd) + ": unknown field \"" + it.key() + "\" (expected " +
                               (list.empty() ? std::string("none") : list) + ")");
        }
    }
}

void onlyFields(const Json& cmd, std::initializer_list<const char*> allowed) {
    onlyFields(cmd, allowed, {});
}

} // namespace faultline::core::args
