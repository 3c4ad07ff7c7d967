#include "core/selection/cutting_box.hpp"

namespace faultline::core {

std::string_view boxModeName(BoxMode mode) { return mode == BoxMode::Keep ? "keep" : "cut"; }

std::optional<BoxMode> parseBoxMode(std::string_view text) {
    if (text == "keep")
        return BoxMode::Keep;
    if (text == "cut")
        return BoxMode::Cut;
    return std::nullopt;
}

} // namespace faultline::core
