// Fault tables for `export.csv` (what=faults, fault_metrics, fault_tracks) and JSON for the same
// data. Text only: writing the file (atomically) is the caller's job.
#pragma once

#include "core/faults/fault.hpp"
#include "core/faults/metrics.hpp"
#include "core/faults/tracking.hpp"

#include <nlohmann/json.hpp>

#include <span>
#include <string>

namespace faultline::core {

// Header `id,fault`; one row per member, faults in the given order, ids ascending.
std::string faultsCsv(std::span<const Fault> faults);

// The columns of faultMetricsCsv, in order (see metrics.hpp for the definitions):
//   frame,fault,count,dip,dip_direction,strike,thickness,area,throw,net_slip,dip_slip,
//   strike_slip,throw_status,hw_samples,fw_samples,centroid_x,centroid_y,centroid_z,
//   min_x,min_y,min_z,max_x,max_y,max_z,normal_x,normal_y,normal_z,eigen_0,eigen_1,eigen_2,
//   mean_radius,broken,seed_frame,seed_x,seed_y,seed_z,length,height
// One row per (frame, fault), frame-major. The seed columns repeat the fault's seed on each
// of its rows (empty seed_frame and NaN point when none). Undefined numbers are written NaN;
// other reals with 9 significant digits; text fields quoted when they need it (RFC 4180).
std::string faultMetricsCsv(const FaultMetricsSeries& series);
std::string faultMetricsCsvHeader();

// {"frames": N, "faults": [{"name", "seed": {...}|null, "frames": [{...per frame...}]}]},
// with the CSV's column names as keys; NaN becomes null.
nlohmann::json faultMetricsJson(const FaultMetricsSeries& series);

// Header frame,fault,present,candidate,candidate_size,shared,jaccard,precision,recall; a row
// per (frame, fault), frame-major as the metrics; candidate -1 when no candidate shares an id.
std::string faultTracksCsv(std::span<const Fault> faults, std::span<const FaultTrack> tracks);

// [{"name", "frames": [{"frame","present","candidate","candidate_size","shared","jaccard",
//   "precision","recall"}]}]; candidate -1 when no candidate shares an id.
nlohmann::json faultTracksJson(std::span<const Fault> faults, std::span<const FaultTrack> tracks);

// Header frame,kind,faults; a row per event (faultEvents order), kind appeared|linked|split,
// faults the names involved joined with ';'.
std::string faultEventsCsv(std::span<const Fault> faults, std::span<const FaultEvent> events);

} // namespace faultline::core
