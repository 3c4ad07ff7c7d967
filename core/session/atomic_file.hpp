// Atomic file writes: the content goes to a temporary file in the same folder, is flushed to
// disk, then renamed over the target, so a crash leaves either the old or the new file.
#pragma once

#include <string>
#include <string_view>

namespace faultline::core {

// Throws std::runtime_error naming the path and the system error.
void writeFileAtomically(const std::string& path, std::string_view content);

} // namespace faultline::core
