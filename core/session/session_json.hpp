// Session files (*.faultline.json): SessionState to and from one JSON document with a schema
// version. Loading validates every value and builds a whole new state, or throws: a session is
// never half-applied. Data paths are stored relative to the session file where possible.
#pragma once

#include "core/session/session_state.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace faultline::core {

// `baseDir`: the folder relative data paths are written against (the session file's folder).
nlohmann::json sessionToJson(const SessionState& state, const std::string& baseDir);

// Throws InputError (with `path` for messages) on a corrupt document, an unknown or newer
// schema, or any invalid value; older schemas are migrated.
SessionState sessionFromJson(const nlohmann::json& doc, const std::string& baseDir,
                             const std::string& path);

// One item of a session, as stored (also the payload of ops that restore a deleted item);
// views, cameras, boxes, thresholds, faults and surface settings have their codecs in items/.
// `where` and `path` name the item in errors (InputError).

// Reads and parses a session file (size and nesting bounded) and validates it.
SessionState loadSessionFile(const std::string& path);
// Writes atomically (temp file, fsync, rename).
void saveSessionFile(const SessionState& state, const std::string& path);

// Parses JSON text with bounded nesting; throws InputError naming the byte offset.
nlohmann::json parseJsonText(const std::string& text, const std::string& path,
                             std::size_t maxDepth = 64);

} // namespace faultline::core
