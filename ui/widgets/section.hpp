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
// ImGui::BeginTable for a table that scrolls (ScrollX/ScrollY: it lives in a child window),
// `height` pixels high, the panel's width. Dear ImGui 1.86 asserts in TableUpdateLayout when
// such a table lies wholly outside its window's visible part (the panel scrolled past it: found
// by the soak test); there this only keeps its place (a Dummy) and returns false.
bool beginScrollingTable(const char* id, int columns, int flags, float height);

} // namespace faultline::ui
