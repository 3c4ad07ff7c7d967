// The ops a session knows: each name's handler and whether it changes state (a state op returns
// the command that undoes it; an action, such as an export, returns null). The built-in ops
// register themselves from session_ops_*.cpp; a layer above core adds its own (the UI library
// adds "render"). Owned by Session (issue 39).
#pragma once

#include "core/session/command_args.hpp"

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

class Session;

class OpRegistry {
  public:
    using Handler = std::function<Json(Session&, const Json& cmd)>;
    struct Entry {
        Handler handler;
        bool changesState = false;
    };

    // Adds or replaces `op`.
    void add(const std::string& op, Handler handler, bool changesState) {
        m_ops[op] = Entry{std::move(handler), changesState};
    }
    // Null for an op nobody registered.
    const Entry* find(std::string_view op) const {
        const auto it = m_ops.find(op);
        return it == m_ops.end() ? nullptr : &it->second;
    }
    // The registered names, sorted.
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& [name, e] : m_ops)
            out.push_back(name);
        return out;
    }

  private:
    std::map<std::string, Entry, std::less<>> m_ops;
};

} // namespace faultline::core
