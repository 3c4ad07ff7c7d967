// Fault candidates: groups of the visible spheres of a frame that the user accepts as faults.
// Network (the default): faults followed by their orientation, apart where they cross or end
// against each other (fault_network.hpp). Connected: components of spheres linked when
// |c_i - c_j| < link * (r_i + r_j). Largest first.
#pragma once

#include "core/faults/fault.hpp"
#include "core/model/frame.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

// Defaults of the journal's fault.candidates, shared by export.csv fault_tracks and the Faults
// panel: link k, smallest candidate kept, names prefix + "1".."n".
inline constexpr double kDefaultCandidateLink = 1.1;
inline constexpr std::size_t kDefaultCandidateMinSize = 10;
inline constexpr std::string_view kDefaultCandidatePrefix = "C";

inline constexpr double kDefaultCandidateAngle = 20.0; // degrees

enum class CandidateMethod { Network, Connected };

struct CandidateOptions {
    double link = kDefaultCandidateLink; // k: neighbours when distance < k (r_i + r_j); > 0
    std::size_t minSize = 1;             // groups with fewer spheres are dropped
    CandidateMethod method = CandidateMethod::Network;
    // Network only. angle: largest change of orientation between linked spheres of one fault
    // (and between two pieces joined across a crossing fault), degrees in (0, 90). radius: the
    // neighbourhood whose plane fit gives a sphere its orientation, world units; 0 picks
    // 4 mean sphere diameters.
    double angle = kDefaultCandidateAngle;
    double radius = 0;
};

struct Candidate {
    std::vector<std::int64_t> ids; // particle ids, sorted ascending
    std::size_t size() const { return ids.size(); }
};

struct CandidateSet {
    // Sorted by size, largest first; equal sizes by smallest member id, ascending. The order
    // does not depend on the row order of the frame or on threading.
    std::vector<Candidate> candidates;
    // Per frame row: index into `candidates`, or -1 (hidden, or in a component below minSize).
    std::vector<std::int32_t> rowLabel;
};

// Candidates among the spheres whose visible[row] != 0 (visible.size() == frame.size(),
// asserted). Connected: a sphere with a non-finite centre or radius stands alone; uniform cell
// grid, lock-free union-find, parallel (TBB). Network: such spheres and scattered ones that
// join no fault are left out. Throws std::invalid_argument when link is not a finite number
// > 0, or (network) angle is not in (0, 90) or radius is negative.
CandidateSet findCandidates(const Frame& frame, std::span<const std::uint8_t> visible,
                            const CandidateOptions& options = {});

// Per frame row a group number in [0, groupCount) or -1: groups as candidates, ranked.
CandidateSet candidatesFromGroups(const Frame& frame, std::span<const std::int32_t> groupOfRow,
                                  std::size_t groupCount, std::size_t minSize);

// "network" | "connected", and back; parseCandidateMethod throws std::invalid_argument.
std::string_view candidateMethodName(CandidateMethod method);
CandidateMethod parseCandidateMethod(std::string_view name);

// How sheet-like a group of spheres is. thicknessRatio: the spread across the best-fit plane
// over the smaller spread within it (sqrt of the two smallest covariance eigenvalues' ratio):
// near 0 for a thin band, 1 for a blob as thick as it is wide. A diffuse group (ratio above
// kDiffuseThicknessRatio) is distributed damage filling a volume, not a fault surface: its dip
// says little (issue 41: sub-vertical "faults" in the graben's centre). Measured on the demo's
// last frame at broken_bonds >= 3: its four faults 0.18-0.20, the graben centres' damage 0.33
// and 0.39. In a section model (the plane holds the thin axis; the ratio is then across over
// along the fault) real shear bands are thick for their length: LAMMPS sandbox bands read
// 0.16-0.35 at the 85th-95th percentile of their strain, so there the limit is higher.
inline constexpr double kDiffuseThicknessRatio = 0.3;
inline constexpr double kDiffuseSectionThicknessRatio = 0.5;
// A candidate dipping less than this many degrees is flagged sub-horizontal: in a real run a
// layer along the model's free surface (which creeps as the block stretches) or its base, more
// often than a fault (issue 37); in a shear box it is the shear zone itself. Flagged, not left
// out.
inline constexpr double kSubHorizontalDip = 15.0;
struct CandidateShape {
    bool valid = false; // >= 3 members in the frame with a determined plane
    double dip = 0, dipDirection = 0;
    double thicknessRatio = 0;
    bool diffuse = false;
    bool subHorizontal = false; // dip below kSubHorizontalDip
};
CandidateShape candidateShape(const Frame& frame, std::span<const std::int64_t> ids);
// "diffuse: its spheres fill a volume (thickness 0.62 of its width), not one fault plane", or "".
std::string diffuseNote(const CandidateShape& shape);
// What an accepted candidate's notes say of its shape: diffuseNote, and for a sub-horizontal one
// "sub-horizontal: dips 2.0 degrees; ...", joined by "; "; "" for a dipping sheet.
std::string shapeNote(const CandidateShape& shape);

// The n-th of a sequence of distinct colours (golden-angle hues), for showing candidates.
std::array<float, 3> candidateColor(std::size_t index);

// The journal's `fault.candidates` acceptance: faults named prefix + "1".."n" (largest first),
// coloured candidateColor(i), empty notes (the op adds shapeNote's), visible. Name clashes are
// the caller's to resolve.
std::vector<Fault> faultsFromCandidates(std::span<const Candidate> candidates,
                                        std::string_view prefix);

} // namespace faultline::core
