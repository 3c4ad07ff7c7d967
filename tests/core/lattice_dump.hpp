// The small LAMMPS dump the session and workbench tests open: a 4x4x4 cubic lattice of radius
// 0.5 (ids 1..64, x,y,z in 0..3) over 3 frames; strain = x/3 + frame, layer = z (integers).
#pragma once

#include <string>

namespace faultline::test {

inline std::string latticeDump() {
    std::string text;
    for (int t = 0; t < 3; ++t) {
        text += "ITEM: TIMESTEP\n" + std::to_string(t * 100) +
                "\nITEM: NUMBER OF ATOMS\n64\nITEM: BOX BOUNDS pp pp pp\n0 3\n0 3\n0 3\n"
                "ITEM: ATOMS id x y z radius strain layer\n";
        int id = 1;
        for (int z = 0; z < 4; ++z)
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x)
                    text += std::to_string(id++) + " " + std::to_string(x) + " " +
                            std::to_string(y) + " " + std::to_string(z) + " 0.5 " +
                            std::to_string(x / 3.0 + t) + " " + std::to_string(z) + "\n";
    }
    return text;
}

// Two frames of an n x n x n unit lattice (ids 1..n^3, columns id x y z radius), every sphere of
// the radius given, the second frame sheared by 0.01 (x += 0.01 z): radii of 20 or 0.0005 make
// one whose radii look like another unit than its centres.
inline std::string shearedLatticeDump(int n, const std::string& radius) {
    std::string text;
    const std::string count = std::to_string(n * n * n), top = std::to_string(n - 0.5);
    for (int t = 0; t < 2; ++t) {
        text += "ITEM: TIMESTEP\n" + std::to_string(t) + "\nITEM: NUMBER OF ATOMS\n" + count +
                "\nITEM: BOX BOUNDS ff ff ff\n-0.5 " + top + "\n-0.5 " + top + "\n-0.5 " + top +
                "\nITEM: ATOMS id x y z radius\n";
        int id = 1;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    text += std::to_string(id++) + " " + std::to_string(x + 0.01 * t * z) + " " +
                            std::to_string(y) + " " + std::to_string(z) + " " + radius + "\n";
    }
    return text;
}

} // namespace faultline::test
