// CuttingBox: a named axis-aligned region in world coordinates that keeps or cuts spheres.
// Visibility rules (JOURNAL.md): union of enabled keep boxes, minus enabled cut boxes; inclusive.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace faultline::core {

enum class BoxMode { Keep, Cut };

std::string_view boxModeName(BoxMode mode);            // "keep" | "cut"
std::optional<BoxMode> parseBoxMode(std::string_view); // nullopt when neither

struct CuttingBox {
    std::string name;
    std::array<double, 3> min{0, 0, 0};
    std::array<double, 3> max{0, 0, 0};
    BoxMode mode = BoxMode::Keep;
    bool enabled = true;

    bool contains(double x, double y, double z) const {
        return x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] && z >= min[2] &&
               z <= max[2];
    }
    bool operator==(const CuttingBox&) const = default;
};

} // namespace faultline::core
