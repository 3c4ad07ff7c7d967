// The demo model: a 3-D bonded-sphere extension block (extensionDemoOptions), generated once into
// the per-user data folder and reused, so a fresh install has realistic data to open.
#pragma once

#include "core/synth/extension_model.hpp"

#include <optional>
#include <string>

namespace faultline::core {

// $XDG_DATA_HOME/faultline/demo, or ~/.local/share/faultline/demo. Throws std::runtime_error when
// neither XDG_DATA_HOME nor HOME is set.
std::string demoModelFolder();

// The demo's dump file when a complete demo of this version exists, else nothing.
std::optional<std::string> existingDemoModel();

// Returns the demo's dump file, generating it first when missing (one to two minutes; progress is
// reported and may cancel, throwing GenerationCancelled). Generation writes into a temporary
// folder renamed into place, so an interrupted run never leaves a half demo behind.
std::string ensureDemoModel(const ProgressCallback& progress = {});

} // namespace faultline::core
