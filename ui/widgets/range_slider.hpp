// RangeSlider: one track with a low and a high handle (thresholds, box extents). Reports the
// values while dragging and when the drag ends, so callers preview and then emit one command.
#pragma once

namespace faultline::ui {

struct RangeEdit {
    bool changed = false;  // the values moved this frame
    bool released = false; // the drag ended this frame (commit now)
};

// `lo`/`hi` are edited in place, kept within [min, max] while dragged, low <= high; integer
// ranges move by whole values. `format` formats the labels drawn on the track ("%.3g").
RangeEdit rangeSlider(const char* id, double* lo, double* hi, double min, double max, bool integer,
                      float width, const char* format = "%.4g");

} // namespace faultline::ui
