// FrameLoader: how the fault analyses reach the frames of a time series without holding them all.
// Dataset::frame fits (bind it in a lambda); it must be safe to call from several threads.
#pragma once

#include "core/model/frame.hpp"

#include <cstddef>
#include <functional>
#include <memory>

namespace faultline::core {

using FrameLoader = std::function<std::shared_ptr<const Frame>(std::size_t frame)>;

} // namespace faultline::core
