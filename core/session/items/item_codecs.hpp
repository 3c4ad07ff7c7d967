// Every session item's codec (one header each), and reading a command into an item with them.
#pragma once

#include "core/session/items/box_codec.hpp"
#include "core/session/items/camera_codec.hpp"
#include "core/session/items/fault_codec.hpp"
#include "core/session/items/item_reader.hpp"
#include "core/session/items/strain_codec.hpp"
#include "core/session/items/surface_codec.hpp"
#include "core/session/items/threshold_codec.hpp"
#include "core/session/items/view_codec.hpp"

namespace faultline::core::items {

// `item` with the fields of `object` read into it and checked (patch, then validate); errors
// become CommandErrors naming the op and the field (`prefix`: the object's path in the command).
template <typename T>
T patchedFrom(const std::string& op, T item, const Json& object, const std::string& prefix,
              std::initializer_list<const char*> required) {
    try {
        const ItemReader fields(object, prefix);
        for (const char* f : required)
            fields.require(f);
        patch(item, fields);
        validate(item);
    } catch (const ItemError& e) {
        throw CommandError(commandMessage(op, e));
    }
    return item;
}

// `item` with the command's own fields read into it and checked.
template <typename T>
T patched(const std::string& op, T item, const Json& cmd,
          std::initializer_list<const char*> required = {}) {
    return patchedFrom(op, std::move(item), cmd, {}, required);
}

// An item carried whole in one of the command's fields (view.restore's "view").
template <typename T>
T patchedField(const std::string& op, T item, const Json& cmd, const char* field,
               std::initializer_list<const char*> required = {}) {
    return patchedFrom(op, std::move(item), args::require(cmd, field), std::string(field) + ".",
                       required);
}

// Checks an item a command built field by field (validate), as a CommandError naming the op.
template <typename T> void checked(const std::string& op, const T& item) {
    try {
        validate(item);
    } catch (const ItemError& e) {
        throw CommandError(commandMessage(op, e));
    }
}

} // namespace faultline::core::items
