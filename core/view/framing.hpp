// What a view fitted to a frame frames: the box of the spheres' centres, leaving out the few
// far strays a granular run throws (grains that fall out of an open model, ejected from a free
// surface). Those are still drawn (the clip planes enclose every sphere); they only no longer
// shrink the model to a speck in the middle of the view, and scrubbing while they fly does not
// zoom out frame after frame.
//
// A stray: a centre farther than the bulk's extent beyond the bulk on some axis, the bulk being
// the 5th to 95th percentile of the centres along that axis. A model with no such spheres (a
// packed block, a heap, a cone up to its apex) is framed by all of its finite centres, as before;
// so is one whose "strays" would be more than 5 % of it.
#pragma once

#include "core/model/frame.hpp"

#include <array>
#include <cstddef>

namespace faultline::core {

struct Framing {
    std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0}; // of the centres framed
    std::size_t strays = 0;                         // centres left out
};

// Of the finite centres of `frame` (all zero for a frame without one).
Framing framingBounds(const Frame& frame);

} // namespace faultline::core
