// Whether a window can be opened here (a display and OpenGL), and if not, why.
#pragma once

#include <string>

namespace faultline::ui {

bool displayAvailable(std::string& why);

} // namespace faultline::ui
