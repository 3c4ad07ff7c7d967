// Small drawing helpers shared by panels: a titled separator, a muted hint with a tooltip.
#pragma once

#include <imgui.h> // IM_FMTARGS

#include <string>

namespace faultline::ui {

// "Title ------" across the panel (Dear ImGui 1.86 has no SeparatorText).
void sectionHeader(const std::string& title);
// Muted text that wraps at the panel's edge (hints, counts, explanations).
void hint(const char* format, ...) IM_FMTARGS(1);
// A "(?)" that shows `text` when hovered.
void helpMarker(const char* text);

} // namespace faultline::ui
