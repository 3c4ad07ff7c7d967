// Reading a command's arguments with errors that say which field was wrong and what was
// expected. Commands come from users' journals: every field is checked before use.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace faultline::core {

// A command that cannot run: bad arguments, or a state that does not allow it.
class CommandError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

using Json = nlohmann::json;

namespace args {
const Json& require(const Json& cmd, const char* field);
std::string string(const Json& cmd, const char* field);
std::optional<std::string> optionalString(const Json& cmd, const char* field);
double number(const Json& cmd, const char* field);
std::optional<double> optionalNumber(const Json& cmd, const char* field);
long long integer(const Json& cmd, const char* field);
std::optional<long long> optionalInteger(const Json& cmd, const char* field);
std::optional<bool> optionalBool(const Json& cmd, const char* field);
std::array<double, 3> vec3(const Json& cmd, const char* field);
std::optional<std::array<double, 3>> optionalVec3(const Json& cmd, const char* field);
std::vector<std::int64_t> ids(const Json& cmd, const char* field);
std::vector<std::string> strings(const Json& cmd, const char* field);
// Fails on any field not in `allowed` (a typo in a journal must not pass silently).
void onlyFields(const Json& cmd, std::initializer_list<const char*> allowed);
// The same with an item's fields (items/*_codec.hpp: fieldNames) and the command's own keys.
void onlyFields(const Json& cmd, std::initializer_list<const char*> keys,
                const std::vector<std::string>& itemFields);
} // namespace args

} // namespace faultline::core
