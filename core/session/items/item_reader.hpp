// Reading session items (camera, box, threshold, ...) from JSON, for the ops, the session files
// and the workbench's previews alike: one reader per item (items/*_codec.hpp), whose errors name
// the field's path within the item. Callers add where the item came from: a command
// (commandMessage: `box.add: "min" must be ...`) or a file (fileMessage: `boxes[0].min: ...`).
#pragma once

#include "core/session/command_args.hpp" // Json, CommandError

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace faultline::core::items {

// A field that cannot be read (Kind::Field: wrong type or missing), or a rule the item breaks
// (Kind::Rule: min above max, a camera looking from below -90 degrees, ...).
class ItemError : public std::runtime_error {
  public:
    enum class Kind { Field, Rule };
    ItemError(Kind kind, std::string path, std::string what, std::string found = {});
    Kind kind;
    std::string path;  // within the item: "min", "camera.fov_y"
    std::string what;  // "must be an array of 3 numbers"
    std::string found; // the value found, as JSON text (Field errors; may be empty)
};

// `op: "field" what, found X` (a field) or `op: field what` (a rule).
std::string commandMessage(const std::string& op, const ItemError& e);
// `where.field: what` (where: the item's place in the file, e.g. "boxes[0]").
std::string fileMessage(const std::string& where, const ItemError& e);

// The fields of one JSON object. read() leaves the value alone when the field is absent, so
// one patch function reads a whole item (every field given) and a change to it (some given).
class ItemReader {
  public:
    // `prefix`: the object's path within the item ("camera." for a view's camera).
    explicit ItemReader(const Json& obj, std::string prefix = {});
    bool has(const char* field) const { return m_obj.contains(field); }
    const Json& get(const char* field) const; // fails when missing
    void require(const char* field) const { (void)get(field); }
    void read(const char* field, std::string& out) const;
    void read(const char* field, double& out) const;
    void read(const char* field, bool& out) const;
    void read(const char* field, std::array<double, 3>& out) const;
    void read(const char* field, std::array<float, 3>& out) const;
    // An array field; an empty one when the field is absent.
    const Json& array(const char* field) const;
    // A name standing for one of a set (a kernel, a colour map, a mode): `parse` gives the value
    // or nothing, and nothing fails with `what`.
    template <typename T, typename Parse>
    void readNamed(const char* field, T& out, Parse parse, const char* what) const {
        if (!has(field))
            return;
        std::string name;
        read(field, name);
        const auto parsed = parse(name);
        if (!parsed)
            fail(field, what, &get(field));
        out = *parsed;
    }
    std::string path(const char* field) const { return m_prefix + field; }
    [[noreturn]] void fail(const char* field, const std::string& what,
                           const Json* found = nullptr) const;

  private:
    const Json& m_obj;
    std::string m_prefix;
};

[[noreturn]] void breaks(const std::string& path, const std::string& what);

// An item's fields declared once (issue 39): each field's name, its value as JSON and how it is
// read, from which come the item's toJson, its patch and the fields a command accepts.
template <typename T> struct Field {
    const char* name;
    Json (*get)(const T&);                                 // the field's value
    void (*read)(T&, const ItemReader&, const char* name); // reads it, when present
};
// A field that is one member, written as JSON and read with ItemReader::read as it is.
template <typename T, auto Member> Json memberJson(const T& item) { return Json(item.*Member); }
template <typename T, auto Member>
void readMember(T& item, const ItemReader& reader, const char* name) {
    reader.read(name, item.*Member);
}
template <typename T, auto Member> constexpr Field<T> member(const char* name) {
    return {name, memberJson<T, Member>, readMember<T, Member>};
}
template <typename T, std::size_t N> Json fieldsToJson(const T& item, const Field<T> (&table)[N]) {
    Json j = Json::object();
    for (const Field<T>& f : table)
        j[f.name] = f.get(item);
    return j;
}
template <typename T, std::size_t N>
void patchFields(T& item, const ItemReader& reader, const Field<T> (&table)[N]) {
    for (const Field<T>& f : table)
        f.read(item, reader, f.name);
}
template <typename T, std::size_t N>
std::vector<std::string> fieldNames(const Field<T> (&table)[N]) {
    std::vector<std::string> names;
    for (const Field<T>& f : table)
        names.emplace_back(f.name);
    return names;
}

} // namespace faultline::core::items
