#include "core/session/items/item_reader.hpp"

#include <cmath>

namespace faultline::core::items {

ItemError::ItemError(Kind k, std::string p, std::string w, std::string f)
    : std::runtime_error(p + " " + w), kind(k), path(std::move(p)), what(std::move(w)),
      found(std::move(f)) {}

std::string commandMessage(const std::string& op, const ItemError& e) {
    if (e.kind == ItemError::Kind::Rule)
        return op + ": " + e.path + " " + e.what;
    return op + ": \"" + e.path + "\" " + e.what + (e.found.empty() ? "" : ", found " + e.found);
}

std::string fileMessage(const std::string& where, const ItemError& e) {
    std::string at = where;
    if (!e.path.empty())
        at += (at.empty() ? "" : ".") + e.path;
    return (at.empty() ? std::string("document") : at) + ": " + e.what;
}

void breaks(const std::string& path, const std::string& what) {
    throw ItemError(ItemError::Kind::Rule, path, what);
}

ItemReader::ItemReader(const Json& obj, std::string prefix)
    : m_obj(obj), m_prefix(std::move(prefix)) {
    if (!obj.is_object()) {
        std::string path = m_prefix;
        if (!path.empty() && path.back() == '.')
            path.pop_back();
        throw ItemError(ItemError::Kind::Field, path,
                        "must be an object, found " + std::string(obj.type_name()));
    }
}

void ItemReader::fail(const char* field, const std::string& what, const Json* found) const {
    throw ItemError(ItemError::Kind::Field, path(field), what, found ? found->dump() : "");
}

const Json& ItemReader::get(const char* field) const {
    auto it = m_obj.find(field);
    if (it == m_obj.end())
        fail(field, "is missing");
    return *it;
}

namespace {
bool finiteNumber(const Json& v) { return v.is_number() && std::isfinite(v.get<double>()); }
} // namespace

void ItemReader::read(const char* field, std::string& out) const {
    if (!has(field))
        return;
    const Json& v = get(field);
    if (!v.is_string())
        fail(field, "must be a string", &v);
    out = v.get<std::string>();
}

void ItemReader::read(const char* field, double& out) const {
    if (!has(field))
        return;
    const Json& v = get(field);
    if (!finiteNumber(v))
        fail(field, "must be a finite number", &v);
    out = v.get<double>();
}

void ItemReader::read(const char* field, bool& out) const {
    if (!has(field))
        return;
    const Json& v = get(field);
    if (!v.is_boolean())
        fail(field, "must be true or false", &v);
    out = v.get<bool>();
}

void ItemReader::read(const char* field, std::array<double, 3>& out) const {
    if (!has(field))
        return;
    const Json& v = get(field);
    if (!v.is_array() || v.size() != 3)
        fail(field, "must be an array of 3 numbers", &v);
    std::array<double, 3> next{};
    for (std::size_t k = 0; k < 3; ++k) {
        if (!finiteNumber(v[k]))
            fail(field, "must hold finite numbers", &v);
        next[k] = v[k].get<double>();
    }
    out = next;
}

const Json& ItemReader::array(const char* field) const {
    static const Json kEmpty = Json::array();
    if (!has(field))
        return kEmpty;
    const Json& v = get(field);
    if (!v.is_array())
        fail(field, "must be an array", &v);
    return v;
}

void ItemReader::read(const char* field, std::array<float, 3>& out) const {
    std::array<double, 3> d{out[0], out[1], out[2]};
    read(field, d);
    out = {static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2])};
}

} // namespace faultline::core::items
