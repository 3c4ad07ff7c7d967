// Text that fits its place: labels shortened with "..." where the column or window is too narrow
// (the whole text in a tooltip), and rows of buttons that flow onto the next line instead of
// running past the panel's edge. The layout test (tests/ui/layout_test.cpp) checks that nothing
// is cut off.
#pragma once

#include <string>
#include <vector>

namespace faultline::ui {

// `text` shortened to at most `width` pixels in the current font, ending in "..." when cut.
std::string elided(const std::string& text, float width);
// Draws `text` shortened to the space left on this line (or `width` when given); when
// shortened, hovering shows all of it. Returns whether it was shortened.
bool textElided(const std::string& text, float width = 0.0f);
// `text` broken into lines no wider than `width` at spaces and newlines only: ImGui's own
// wrapping also breaks after '.', which split "58.503" into "58." and "503". A word wider than
// `width` keeps a line of its own.
std::vector<std::string> wrapAtSpaces(const std::string& text, float width);
// Draws `text` wrapped at spaces to the space left in the window or column.
void textWrappedAtSpaces(const std::string& text);
// Before an item that is not the first of a row: stays on the row when an item `width` pixels
// wide still fits, else starts a new row. `buttonWidth(label)` is the width of a button.
void flowSameLine(float width);
float buttonWidth(const char* label);
// The width of a checkbox with its label (also of a field `fieldWidth` wide with its label).
float checkboxWidth(const char* label);
float labelledWidth(float fieldWidth, const char* label);
// ImGui::CollapsingHeader with its label shortened to the window's width (a header's label
// past the edge is cut without a word and widens the window's content); the whole label on
// hover. `flags`: ImGuiTreeNodeFlags.
bool collapsingHeader(const std::string& label, int flags = 0);

} // namespace faultline::ui
