// StrainSpec: one set of variables derived from motion (strain.add): against which frame, over
// which neighbours, under which names. Plain data; the session holds a list, the dataset
// computes the columns (core/motion/strain_from_motion.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace faultline::core {

struct StrainSpec {
    bool relative = false;   // false: against frame `reference`; true: `reference` frames away
    long long reference = 0; // since_frame (>= 0) or since_offset (non-zero)
    double cutoff = 0;       // neighbour distance in the reference frame; 0: automatic
    std::string prefix;      // put before each variable's name ("inc_shear_strain")
    bool operator==(const StrainSpec&) const = default;

    // The reference frame for `frame` of `count` frames; nothing when it lies outside the data
    // (the variables are NaN there).
    std::optional<std::size_t> referenceFor(std::size_t frame, std::size_t count) const;
    // One of its variables under its prefix: variable(kShearStrain) is "inc_shear_strain".
    std::string variable(std::string_view name) const { return prefix + std::string(name); }
};

// The variables each spec adds, without its prefix, in column order.
// ref_x, ref_y, ref_z: where each sphere was in the reference frame, as the minimum image next to
// where it is now (issue 41: reference positions are variables too; fault throw measures the
// offset of these since the reference frame where the file has no x0, y0, z0).
inline constexpr std::string_view kShearStrain = "shear_strain"; // what shows faults best
inline constexpr std::array<std::string_view, 7> kStrainVariables = {
    kShearStrain, "volumetric_strain", "d2min", "displacement", "ref_x", "ref_y", "ref_z"};

} // namespace faultline::core
