// Local shear strain of each sphere from how its neighbourhood deformed (initial vs current
// neighbour vectors): the von Mises invariant of the best-fit Green-Lagrange strain tensor.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace faultline::core {

// Neighbours of each sphere as compressed rows: partners of i are
// partners[offsets[i] .. offsets[i + 1]).
struct NeighbourTable {
    std::vector<std::uint32_t> offsets;
    std::vector<std::uint32_t> partners;
};

// Both directions of every pair, each row in increasing partner order.
NeighbourTable neighbourTableFromPairs(std::size_t sphereCount,
                                       const std::vector<std::array<std::uint32_t, 2>>& pairs);

// For sphere i with neighbour vectors X_k (initial) and Y_k (current): F = (sum Y X^T)(sum X
// X^T)^-1, E = (F^T F - I) / 2, and the result is sqrt(Exy^2 + Eyz^2 + Exz^2 +
// ((Exx-Eyy)^2 + (Eyy-Ezz)^2 + (Ezz-Exx)^2) / 6). Zero where the neighbours do not span 3-D.
// Runs in parallel; the result does not depend on the thread count.
std::vector<double> vonMisesShearStrain(const std::vector<std::array<double, 3>>& initial,
                                        const std::vector<std::array<double, 3>>& current,
                                        const NeighbourTable& neighbours);

} // namespace faultline::core
