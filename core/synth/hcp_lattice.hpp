// HcpLattice: equal spheres in hexagonal close packing with their nearest-neighbour pairs.
// Close-packed planes are x-z planes stacked ABAB along y, so a thin slab shows hexagonal rows.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace faultline::core {

struct HcpLattice {
    double radius = 1.0;
    int columns = 0; // spheres per row, along x
    int layers = 0;  // close-packed planes, along y
    int rows = 0;    // rows per plane, along z
    // Index of (column c, layer l, row r) is (r * layers + l) * columns + c.
    std::vector<std::array<double, 3>> positions;
    std::vector<int> rowOf;   // z row of each sphere (0 at the base)
    std::vector<int> layerOf; // y plane of each sphere
    // Touching pairs (i < j), in increasing i then j: up to 12 per sphere.
    std::vector<std::array<std::uint32_t, 2>> pairs;
    // The box that holds every sphere: [0, hi] on each axis (spheres touch the low faces).
    std::array<double, 3> hi{0, 0, 0};

    std::size_t size() const { return positions.size(); }
};

// Spheres of `radius` with centres at x = R(1 + 2c + (r odd) + (l odd)),
// y = R(1 + 2 l sqrt(2/3)), z = R(1 + sqrt(3) r + (l odd) / sqrt(3)).
HcpLattice makeHcpLattice(int columns, int layers, int rows, double radius = 1.0);

} // namespace faultline::core
