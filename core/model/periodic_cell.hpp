// The periodic cell of a simulation box, for the minimum-image convention: edge vectors
// a = (lx,0,0), b = (xy,ly,0), c = (xz,yz,lz) (LAMMPS' triclinic convention), and which axes wrap.
#pragma once

#include "core/model/frame.hpp"

#include <cmath>

namespace faultline::core {

struct PeriodicCell {
    bool any = false;
    bool periodic[3] = {false, false, false};
    double lx = 0, ly = 0, lz = 0, xy = 0, xz = 0, yz = 0;

    PeriodicCell() = default;
    explicit PeriodicCell(const SimulationBox& box) {
        if (!box.known)
            return;
        lx = box.hi[0] - box.lo[0];
        ly = box.hi[1] - box.lo[1];
        lz = box.hi[2] - box.lo[2];
        if (box.triclinic) {
            xy = box.xy;
            xz = box.xz;
            yz = box.yz;
        }
        const double length[3] = {lx, ly, lz};
        for (int a = 0; a < 3; ++a) {
            periodic[a] = box.periodic[a] && length[a] > 0;
            any = any || periodic[a];
        }
    }

    // The shortest image of a displacement: whole cells removed along periodic axes, z first
    // since c carries x and y tilt, then y, then x.
    // Most spheres move far less than half a cell: they skip the division.
    void wrap(double& dx, double& dy, double& dz) const {
        if (periodic[2] && std::fabs(dz) > 0.5 * lz) {
            const double n = std::round(dz / lz);
            dz -= n * lz;
            dy -= n * yz;
            dx -= n * xz;
        }
        if (periodic[1] && std::fabs(dy) > 0.5 * ly) {
            const double n = std::round(dy / ly);
            dy -= n * ly;
            dx -= n * xy;
        }
        if (periodic[0] && std::fabs(dx) > 0.5 * lx)
            dx -= std::round(dx / lx) * lx;
    }
};

} // namespace faultline::core
