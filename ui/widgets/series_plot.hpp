// SeriesPlot: values over the frames of a run as lines (one per fault), with round-number axes,
// a vertical cursor at the current frame, and click-or-drag to pick a frame. NaN values leave
// gaps. Drawn with ImDrawList so labels use the workbench's (scaled) font.
#pragma once

#include <imgui.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>

namespace faultline::ui {

struct PlotLine {
    std::string label;              // in the hover read-out
    std::span<const double> values; // values[frame]; NaN: undefined there
    ImU32 color = IM_COL32(40, 90, 200, 255);
};

// A frame marked on the plot (an event): a thin vertical line, a letter at its top, and its
// text in the hover read-out when the mouse is on that frame.
struct PlotMark {
    std::size_t frame = 0;
    char letter = '*';
    std::string text;
    ImU32 color = IM_COL32(200, 60, 40, 255);
};

struct PlotInput {
    std::optional<std::size_t> frame; // under the mouse while the button is held (or clicked)
    bool released = false;            // the click or drag ended this frame: commit `frame`
};

// The widget fills `size` at the cursor. integerValues: whole-number y ticks (counts).
PlotInput seriesPlot(const char* id, std::span<const PlotLine> lines, std::size_t frameCount,
                     std::size_t cursorFrame, ImVec2 size, bool integerValues, float scale,
                     std::span<const PlotMark> marks = {});

} // namespace faultline::ui
