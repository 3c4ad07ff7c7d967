// Shared helpers of the built-in op implementations (session_ops_*.cpp): how an op reads its
// command and builds its inverse. Not for use outside core/session.
#pragma once

#include "core/faults/candidates.hpp"
#include "core/io/input_error.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"

#include <string>
#include <utility>

namespace faultline::core::detail {

inline void addStateOp(OpRegistry& ops, const char* name, Session::OpHandler h) {
    ops.add(name, std::move(h), true);
}
inline void addAction(OpRegistry& ops, const char* name, Session::OpHandler h) {
    ops.add(name, std::move(h), false);
}
// An op of the contract whose feature has not landed yet: a clear error, never a silent pass.
inline void addNotYet(OpRegistry& ops, const char* name, const char* feature) {
    ops.add(
        name,
        [name = std::string(name), feature = std::string(feature)](Session&, const Json&) -> Json {
            throw CommandError(name + ": not available yet (" + feature + ")");
        },
        false);
}

// "link" and "min_size" of fault.candidates and export.csv fault_tracks, with the journal's
// defaults; a CommandError naming `op` when they are out of range.
CandidateOptions candidateOptionsFrom(const Json& cmd, const char* op);

// InputError from a payload (a restore op) as a CommandError.
template <typename F> auto asCommand(const char* op, F f) -> decltype(f()) {
    try {
        return f();
    } catch (const InputError& e) {
        throw CommandError(std::string(op) + ": " + e.message());
    }
}

} // namespace faultline::core::detail
