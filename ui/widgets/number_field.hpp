// NumberField: a number the user types, committed once. One click puts the cursor in the field;
// Enter or leaving it commits what was typed (one command, not one per keystroke); Escape puts
// the value back and commits nothing; text that is not a number is ignored.
#pragma once

namespace faultline::ui {

// Returns true once when a new value was committed into *value. `format` shows the value
// (printf, e.g. "%.4g"); `empty` is shown greyed when the field is empty (e.g. "auto"), and an
// empty field commits `emptyValue`. `width` 0: ImGui's default width.
bool numberField(const char* label, double* value, const char* format = "%.6g", float width = 0.0f,
                 const char* empty = nullptr, double emptyValue = 0.0);
bool numberField(const char* label, int* value, float width = 0.0f);

} // namespace faultline::ui
