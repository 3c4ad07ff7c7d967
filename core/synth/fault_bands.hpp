// How concentrated damage is: the few narrow dipping bands (in the x-z section) that hold the
// most broken bonds, and their share against the share the same bands would hold of uniform damage.
#pragma once

#include "core/model/frame.hpp"

#include <vector>

namespace faultline::core {

// A straight band in the x-z plane: points with |x sin(dip) + s z cos(dip) - offset| <= width / 2,
// s = +1 for a band dipping towards +x (east), -1 towards -x.
struct DippingBand {
    double dip = 0; // degrees below horizontal
    int towardsPlusX = 1;
    double offset = 0;
    double weight = 0; // weight inside the band when it was picked
};

struct FaultBandMeasure {
    std::vector<DippingBand> bands; // best first, each picked after removing the previous ones
    double damagedShare = 0;        // share of broken bonds inside the bands
    double uniformShare = 0; // share of all spheres inside the best bands found for them alike
    double concentration() const { return uniformShare > 0 ? damagedShare / uniformShare : 0; }
};

struct FaultBandOptions {
    int bands = 4;
    double width = 6.0;                           // full band width, in the frame's length unit
    double minDip = 30, maxDip = 90, dipStep = 1; // degrees
    bool skipBoundaryTypes = true;                // ignore spheres whose `type` column is not 1
};

// Weights are the frame's `broken_bonds` column (asserted present). Greedy: the heaviest band over
// every dip and offset, its spheres removed, then the next. Runs the same search on weight 1 per
// sphere for the uniform share.
FaultBandMeasure measureFaultBands(const Frame& frame, const FaultBandOptions& options = {});

} // namespace faultline::core
