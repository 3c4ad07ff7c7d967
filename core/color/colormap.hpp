// Colour maps for per-sphere variables: named maps, sampling, RGBA8 tables for the GPU, and the
// value range a view maps onto [0, 1] (from the current frame, from all frames, or fixed).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

enum class ColorMapKind {
    BlueRed,   // linear blue -> red, the paper's map
    Viridis,   // perceptually uniform, colour-blind safe
    Diverging, // cool-warm through a light grey: for values around a meaningful middle
    Pastel,    // two pastel shades, non-linear (square root) to spread small values
    Bands,     // alternating bands by value, e.g. initial height to show offset layers
    Gray,      // linear dark -> light grey: for print, or under coloured faults and surfaces
    Palette, // categories (faults, candidates): value k + 0.5 takes palette[k]; not a journal name
};

struct ColorMapSpec {
    ColorMapKind kind = ColorMapKind::BlueRed;
    int bands = 10;                   // Bands only: how many bands cover the range (1..1024)
    std::vector<glm::vec3> palette{}; // Palette only: one colour per category, range [0, size]
    bool operator==(const ColorMapSpec&) const = default;
};

inline constexpr int kMaxBands = 1024;

// The journal's names: "blue-red", "viridis", "diverging", "pastel", "bands", "bands:N", "gray"
// (parse also takes "grey").
std::string colorMapName(const ColorMapSpec& spec);
// Case-insensitive; nullopt for an unknown name or a band count outside 1..kMaxBands.
std::optional<ColorMapSpec> parseColorMap(std::string_view name);
// A map a journal or session may name: parseColorMap without Palette (categories' colours).
std::optional<ColorMapSpec> parseJournalColorMap(std::string_view name);
// Names to offer in a combo box, in display order.
const std::vector<std::string>& colorMapNames();

// Colour (sRGB, 0..1) at t in [0, 1]; t is clamped; NaN gives nanColor(spec).
glm::vec3 sampleColorMap(const ColorMapSpec& spec, double t);
inline constexpr glm::vec3 kNanColor{0.55f, 0.55f, 0.55f};
// What NaN (no value) looks like under a map: kNanColor, except where that grey would pass for
// a value (Gray), which gets a muted ochre instead.
glm::vec3 nanColor(const ColorMapSpec& spec);

// What the GPU samples: continuous maps are `size` texels sampled linearly at t; Bands is a short
// palette sampled with nearest filtering at index floor(t * bandCount) mod palette size.
struct ColorMapTexture {
    std::vector<std::uint8_t> rgba; // width * 4 bytes
    int width = 0;
    bool nearest = false;
    int bandCount = 0; // 0: continuous
};
ColorMapTexture colorMapTexture(const ColorMapSpec& spec, int size = 256);

// RGBA8 table of `size` samples at t = i / (size - 1); for every map (Bands included).
std::vector<std::uint8_t> colorMapTable(const ColorMapSpec& spec, int size);

// ---- value ranges ----

struct ValueRange {
    double low = 0.0;
    double high = 1.0;
    bool operator==(const ValueRange&) const = default;
};

enum class RangeMode {
    CurrentFrame, // min/max of the variable in the frame shown
    AllFrames,    // min/max over every frame, so an animation does not flicker
    Fixed,        // as the user set it
    Percentile,   // the 1st to 99th percentile in the frame shown: a few extremes wash out nothing
};

std::string_view rangeModeName(RangeMode mode); // "frame" | "all" | "fixed" | "percentile"
std::optional<RangeMode> parseRangeMode(std::string_view name);

// The range a view uses. AllFrames falls back to the current frame until the all-frames range
// is known. The result always has low < high (a degenerate range is widened around its value).
ValueRange resolveColorRange(RangeMode mode, ValueRange currentFrame,
                             std::optional<ValueRange> allFrames, ValueRange fixed);

// low < high, widening an empty or inverted range; NaN or infinite bounds give [0, 1].
ValueRange widenDegenerate(ValueRange range);

// Union of two ranges (for accumulating all-frames ranges).
ValueRange unite(ValueRange a, ValueRange b);

// (v - low) / (high - low), not clamped; NaN stays NaN.
inline double normalizeValue(double v, ValueRange range) {
    return (v - range.low) / (range.high - range.low);
}

} // namespace faultline::core
