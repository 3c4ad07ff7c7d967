#include "core/selection/cutting_box.hpp"
#include "core/util/enum_names.hpp"

namespace faultline::core {

namespace {
constexpr EnumName<BoxMode> kBoxModes[] = {{BoxMode::Keep, "keep"}, {BoxMode::Cut, "cut"}};
} // namespace

std::string_view boxModeName(BoxMode mode) { return nameIn(kBoxModes, mode, "cut"); }

std::optional<BoxMode> parseBoxMode(std::string_view text) { return valueIn(kBoxModes, text); }

} // namespace faultline::core
