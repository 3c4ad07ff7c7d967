// The panels of the workbench by id (as saved in the dock layout) and title.
#pragma once

#include <string>
#include <vector>

namespace faultline::ui::panel_ids {

inline constexpr const char* kData = "data";
inline constexpr const char* kHistograms = "histograms";
inline constexpr const char* kBoxes = "boxes";
inline constexpr const char* kThresholds = "thresholds";
inline constexpr const char* kFaults = "faults";
inline constexpr const char* kSurfaces = "surfaces";
inline constexpr const char* kTimeline = "timeline";
inline constexpr const char* kViewports = "viewports";

inline const std::vector<std::string>& all() {
    static const std::vector<std::string> ids{kViewports,  kData,   kBoxes,    kThresholds,
                                              kHistograms, kFaults, kSurfaces, kTimeline};
    return ids;
}

} // namespace faultline::ui::panel_ids
