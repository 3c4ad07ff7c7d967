#include "core/color/colormap.hpp"
#include "core/util/enum_names.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <span>

namespace faultline::core {

namespace {

struct Stop {
    double t;
    glm::vec3 rgb;
};

constexpr glm::vec3 hex(unsigned v) {
    return {float((v >> 16) & 0xff) / 255.0f, float((v >> 8) & 0xff) / 255.0f,
            float(v & 0xff) / 255.0f};
}

// Published 11-step viridis (matplotlib / viridisLite).
constexpr std::array<Stop, 11> kViridis{{{0.0, hex(0x440154)},
                                         {0.1, hex(0x482475)},
                                         {0.2, hex(0x414487)},
                                         {0.3, hex(0x355F8D)},
                                         {0.4, hex(0x2A788E)},
                                         {0.5, hex(0x21918C)},
                                         {0.6, hex(0x22A884)},
                                         {0.7, hex(0x44BF70)},
                                         {0.8, hex(0x7AD151)},
                                         {0.9, hex(0xBDDF26)},
                                         {1.0, hex(0xFDE725)}}};

// Moreland's cool-warm diverging map, five stops.
constexpr std::array<Stop, 5> kCoolWarm{{{0.0, hex(0x3B4CC0)},
                                         {0.25, hex(0x8DB0FE)},
                                         {0.5, hex(0xDDDDDD)},
                                         {0.75, hex(0xF49A7B)},
                                         {1.0, hex(0xB40426)}}};

constexpr glm::vec3 kBlue = hex(0x0D33FF);
constexpr glm::vec3 kRed = hex(0xFF1A0D);
constexpr glm::vec3 kPastelLow = hex(0xAAC8EE);                                // pale blue
constexpr glm::vec3 kPastelHigh = hex(0xF4A09A);                               // pale coral
constexpr std::array<glm::vec3, 2> kBandPalette{hex(0xE3CC9E), hex(0x6B84A6)}; // sand, slate
// Not black: the lowest values still show their shading; not white: the highest stay visible
// on a white background. Linear in sRGB, which is close to even steps of lightness.
constexpr glm::vec3 kGrayLow = hex(0x383838);
constexpr glm::vec3 kGrayHigh = hex(0xE6E6E6);

glm::vec3 lerp(glm::vec3 a, glm::vec3 b, double t) {
    const float f = static_cast<float>(t);
    return a + (b - a) * f;
}

glm::vec3 sampleStops(std::span<const Stop> stops, double t) {
    for (std::size_t i = 1; i < stops.size(); ++i) {
        if (t <= stops[i].t) {
            const double span = stops[i].t - stops[i - 1].t;
            return lerp(stops[i - 1].rgb, stops[i].rgb, (t - stops[i - 1].t) / span);
        }
    }
    return stops.back().rgb;
}

float toLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float toSrgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::uint8_t toByte(float v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

} // namespace

std::string colorMapName(const ColorMapSpec& spec) {
    switch (spec.kind) {
    case ColorMapKind::BlueRed:
        return "blue-red";
    case ColorMapKind::Viridis:
        return "viridis";
    case ColorMapKind::Diverging:
        return "diverging";
    case ColorMapKind::Pastel:
        return "pastel";
    case ColorMapKind::Bands:
        return spec.bands == ColorMapSpec{}.bands ? "bands" : "bands:" + std::to_string(spec.bands);
    case ColorMapKind::Gray:
        return "gray";
    case ColorMapKind::Palette:
        return "palette";
    }
    return "blue-red";
}

std::optional<ColorMapSpec> parseColorMap(std::string_view name) {
    const std::string n = lower(name);
    if (n == "blue-red" || n == "bluered" || n == "blue_red")
        return ColorMapSpec{ColorMapKind::BlueRed};
    if (n == "viridis")
        return ColorMapSpec{ColorMapKind::Viridis};
    if (n == "diverging" || n == "cool-warm" || n == "coolwarm")
        return ColorMapSpec{ColorMapKind::Diverging};
    if (n == "pastel")
        return ColorMapSpec{ColorMapKind::Pastel};
    if (n == "bands")
        return ColorMapSpec{ColorMapKind::Bands};
    if (n == "gray" || n == "grey")
        return ColorMapSpec{ColorMapKind::Gray};
    constexpr std::string_view kBandsPrefix = "bands:";
    if (n.starts_with(kBandsPrefix)) {
        int count = 0;
        const char* first = n.data() + kBandsPrefix.size();
        const char* last = n.data() + n.size();
        auto [ptr, ec] = std::from_chars(first, last, count);
        if (ec != std::errc() || ptr != last || first == last || count < 1 || count > kMaxBands)
            return std::nullopt;
        return ColorMapSpec{ColorMapKind::Bands, count};
    }
    return std::nullopt;
}

const std::vector<std::string>& colorMapNames() {
    static const std::vector<std::string> names{"blue-red", "viridis", "diverging",
                                                "pastel",   "bands",   "gray"};
    return names;
}

glm::vec3 nanColor(const ColorMapSpec& spec) {
    return spec.kind == ColorMapKind::Gray ? hex(0xB88A5C) : kNanColor;
}

glm::vec3 sampleColorMap(const ColorMapSpec& spec, double t) {
    if (std::isnan(t))
        return nanColor(spec);
    t = std::clamp(t, 0.0, 1.0);
    switch (spec.kind) {
    case ColorMapKind::BlueRed:
        return lerp(kBlue, kRed, t);
    case ColorMapKind::Viridis:
        return sampleStops(kViridis, t);
    case ColorMapKind::Diverging:
        return sampleStops(kCoolWarm, t);
    case ColorMapKind::Pastel: {
        // Square root: most spheres of a faulted model have small strain; spread them out.
        // Interpolated in linear light so the middle does not turn muddy.
        const float s = static_cast<float>(std::sqrt(t));
        glm::vec3 out;
        for (int c = 0; c < 3; ++c)
            out[c] = toSrgb(toLinear(kPastelLow[c]) * (1 - s) + toLinear(kPastelHigh[c]) * s);
        return out;
    }
    case ColorMapKind::Bands: {
        const int count = std::clamp(spec.bands, 1, kMaxBands);
        const int band = std::min(static_cast<int>(std::floor(t * count)), count - 1);
        return kBandPalette[static_cast<std::size_t>(band) % kBandPalette.size()];
    }
    case ColorMapKind::Gray:
        return lerp(kGrayLow, kGrayHigh, t);
    case ColorMapKind::Palette: {
        if (spec.palette.empty())
            return kNanColor;
        const int count = static_cast<int>(spec.palette.size());
        return spec.palette[static_cast<std::size_t>(
            std::min(static_cast<int>(std::floor(t * count)), count - 1))];
    }
    }
    return kNanColor;
}

std::vector<std::uint8_t> colorMapTable(const ColorMapSpec& spec, int size) {
    size = std::max(size, 2);
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(size) * 4);
    for (int i = 0; i < size; ++i) {
        const glm::vec3 c = sampleColorMap(spec, double(i) / double(size - 1));
        rgba[i * 4 + 0] = toByte(c.r);
        rgba[i * 4 + 1] = toByte(c.g);
        rgba[i * 4 + 2] = toByte(c.b);
        rgba[i * 4 + 3] = 255;
    }
    return rgba;
}

ColorMapTexture colorMapTexture(const ColorMapSpec& spec, int size) {
    ColorMapTexture tex;
    if (spec.kind == ColorMapKind::Palette && !spec.palette.empty()) {
        tex.width = static_cast<int>(spec.palette.size());
        tex.nearest = true;
        tex.bandCount = tex.width;
        for (const glm::vec3& c : spec.palette)
            tex.rgba.insert(tex.rgba.end(), {toByte(c.r), toByte(c.g), toByte(c.b), 255});
        return tex;
    }
    if (spec.kind == ColorMapKind::Bands) {
        tex.width = static_cast<int>(kBandPalette.size());
        tex.nearest = true;
        tex.bandCount = std::clamp(spec.bands, 1, kMaxBands);
        for (const glm::vec3& c : kBandPalette)
            tex.rgba.insert(tex.rgba.end(), {toByte(c.r), toByte(c.g), toByte(c.b), 255});
        return tex;
    }
    tex.width = std::max(size, 2);
    tex.rgba = colorMapTable(spec, tex.width);
    return tex;
}

namespace {
constexpr EnumName<RangeMode> kRangeModes[] = {{RangeMode::CurrentFrame, "frame"},
                                               {RangeMode::AllFrames, "all"},
                                               {RangeMode::Fixed, "fixed"},
                                               {RangeMode::Percentile, "percentile"}};
} // namespace

std::string_view rangeModeName(RangeMode mode) { return nameIn(kRangeModes, mode, "frame"); }

std::optional<RangeMode> parseRangeMode(std::string_view name) {
    return valueIn(kRangeModes, name, NameCase::Ignore);
}

ValueRange widenDegenerate(ValueRange r) {
    if (!std::isfinite(r.low) || !std::isfinite(r.high))
        return {0.0, 1.0};
    if (r.low > r.high)
        std::swap(r.low, r.high);
    if (r.low == r.high) {
        const double pad = r.low == 0.0 ? 0.5 : std::abs(r.low) * 0.01;
        return {r.low - pad, r.high + pad};
    }
    return r;
}

ValueRange unite(ValueRange a, ValueRange b) {
    return {std::min(a.low, b.low), std::max(a.high, b.high)};
}

ValueRange resolveColorRange(RangeMode mode, ValueRange currentFrame,
                             std::optional<ValueRange> allFrames, ValueRange fixed) {
    switch (mode) {
    case RangeMode::CurrentFrame:
    case RangeMode::Percentile: // the caller's "current frame" range is the percentiles
        return widenDegenerate(currentFrame);
    case RangeMode::AllFrames:
        return widenDegenerate(allFrames ? *allFrames : currentFrame);
    case RangeMode::Fixed:
        return widenDegenerate(fixed);
    }
    return widenDegenerate(currentFrame);
}

std::optional<ColorMapSpec> parseJournalColorMap(std::string_view name) {
    auto map = parseColorMap(name);
    if (map && map->kind == ColorMapKind::Palette)
        return std::nullopt;
    return map;
}

} // namespace faultline::core
