// Small facts about a frame's columns that several panels need: the variables one can choose
// (attributes, then x y z radius), a variable's range and integrality, the model's bounds.
#pragma once

#include "core/model/frame.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

// Attribute columns in file order, then "x", "y", "z", "radius".
std::vector<std::string> variableNames(const core::Frame& frame);

struct VariableInfo {
    double min = 0.0, max = 0.0; // finite values only; min > max when there are none
    bool integer = false;
};
std::optional<VariableInfo> variableInfo(const core::Frame& frame, const std::string& name);

// The variables of recently shown frames with their ranges, computed once per frame (a radius
// range is a pass over every sphere: too slow to repeat every UI frame at 10^6 spheres).
class ColumnCatalog {
  public:
    using Entries = std::vector<std::pair<std::string, VariableInfo>>;
    const Entries& of(const std::shared_ptr<const core::Frame>& frame);
    std::optional<VariableInfo> info(const std::shared_ptr<const core::Frame>& frame,
                                     const std::string& name);

  private:
    std::vector<std::pair<std::shared_ptr<const core::Frame>, Entries>> m_recent; // newest last
};

// Bounds of the sphere centres widened by the largest radius: what a "whole model" box is.
struct ModelBounds {
    std::array<double, 3> lo{0, 0, 0}, hi{1, 1, 1};
};
ModelBounds modelBounds(const core::Frame& frame);
// What fitting a view to the frame frames: core::framingBounds (no far strays), widened by the
// largest radius as modelBounds is.
ModelBounds framedBounds(const core::Frame& frame);
// The same over the rows whose mask byte is non-zero (the visible spheres).
ModelBounds visibleBounds(const core::Frame& frame, const std::vector<std::uint8_t>& mask);

// "12.5 MB" etc.
std::string bytesText(std::size_t bytes);
// A compact number for labels: 4 significant digits, no trailing zeros, exponent when needed.
std::string numberText(double v);

} // namespace faultline::ui
