// Transport buttons drawn as shapes (play, pause, step, first, last), since the default font has
// no such glyphs.
#pragma once

namespace faultline::ui {

enum class Icon { First, Previous, Play, Pause, Next, Last };

// A square button of the frame height; true when clicked.
bool iconButton(const char* id, Icon icon, const char* tooltip);

} // namespace faultline::ui
