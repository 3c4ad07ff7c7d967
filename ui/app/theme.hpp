// The workbench's look: a calm light theme that sits well around white 3-D views, sizes scaled
// for high-DPI screens, and DejaVu Sans when installed (Dear ImGui's bitmap font otherwise).
#pragma once

namespace faultline::ui {

// Resets and scales the ImGui style. `scale` is the monitor's content scale (1 on 96 dpi).
void applyTheme(float scale);
// Adds the UI font at 15 px x scale to the atlas; false when the fallback font was used.
bool loadFonts(float scale);

} // namespace faultline::ui
