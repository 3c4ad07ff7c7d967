// A journal command from its JSON text, for the tests that drive a Session.
#pragma once

#include "core/session/command_args.hpp"

namespace faultline::test {

inline faultline::core::Json cmd(const char* text) { return faultline::core::Json::parse(text); }

} // namespace faultline::test
