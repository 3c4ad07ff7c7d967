// BoundInput: a number field for a threshold bound, where "no bound" (|value| >= 1e30, how
// thresholds store an open end) shows as an empty field hinting "min" or "max".
#pragma once

namespace faultline::ui {

// Returns true once when the user committed a new value (Enter or leaving the field). An empty
// field or "min"/"max" commits the open bound (-1e30 or 1e30); text that is not a number is
// ignored. Integer bounds are rounded (low up, high down) so the threshold keeps whole values.
bool boundInput(const char* id, double* value, bool isHigh, bool integer, float width);

} // namespace faultline::ui
