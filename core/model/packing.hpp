// How a frame's spheres fill their space: the spacing a random close packing of as many spheres
// in the centres' bounds would have, and how the file's radii compare with it. Radii far
// larger than that spacing are likely in another unit than the centres (millimetres beside
// metres): strain from motion refuses the automatic cutoff they give, the Data panel says so,
// and the views draw them scaled down (each sphere would otherwise cover the whole view).
#pragma once

#include "core/model/frame.hpp"

#include <cstddef>
#include <string>
#include <utility>

namespace faultline::core {

// The axis every centre of `f` shares (2-D data), or -1.
int flatAxis(const Frame& f);

// The centres' bounds: their volume (an area in 2-D data, a length on a line) and how many axes
// they span (0: every centre at one point).
std::pair<double, int> centreBounds(const Frame& f);

// The diameter d of a random close packing (0.64) of the frame's spheres in the centres' bounds:
// n * pi d^3 / 6 = 0.64 V; in 2-D, n * pi d^2 / 4 = 0.84 A. 1 where it is undefined.
double packingSpacing(const Frame& f);

// The median of up to `samples` evenly spaced radii; NaN when the file gave none (or none > 0).
double medianRadius(const Frame& f, std::size_t samples = 65536);

// The median diameter over packingSpacing (about 1 in a packed model); NaN without radii, or
// with fewer than kMinSpheresForSpacing spheres (or all at one point). The median of 1,024
// radii: the thresholds below are factors of 4 and 20, and the views ask at each new frame
// (2 us for a million spheres, 0.8 ms with 65,536).
double radiiOverSpacing(const Frame& f);
inline constexpr std::size_t kMinSpheresForSpacing = 64;

// Above this radiiOverSpacing the radii are taken to be in another unit: each sphere overlaps
// dozens of others.
inline constexpr double kRadiiFarOverSpacing = 4.0;
// Below this the radii are taken to be in another unit too (a packing whose outliers widen the
// centres' bounds ten times still reads about 0.5). Drawn as they are: dilute flows exist.
inline constexpr double kRadiiTinyOverSpacing = 1.0 / 20;

// Where the radii look like another unit than the centres (radiiOverSpacing above
// kRadiiFarOverSpacing or below kRadiiTinyOverSpacing), a sentence that says so: "the median
// diameter is 100, about 96 times the spacing of the centres (1.036): are the radii in another
// unit?"; else empty. The Data panel and `faultline info` show it.
std::string radiiUnitNote(const Frame& f);

// What the views multiply the radii by: 1, or where radiiOverSpacing is above
// kRadiiFarOverSpacing, 1 / radiiOverSpacing (the median sphere drawn one spacing wide).
double radiusDrawScale(const Frame& f);

} // namespace faultline::core
