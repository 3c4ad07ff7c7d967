// Issue 37: kinematic truth. The faults of the real DEM runs read from how their spheres moved
// (rigid blocks and the planes between them), without any strain threshold; what the fault
// candidates are checked against (fault_candidates_real_runs_test.cpp).
#include "core/data/dataset.hpp"
#include "core/motion/kinematic_faults.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace faultline::core;

namespace {

using faultline::test::realRunFile;

void print(const char* what, const KinematicResult& k) {
    std::printf("%s: %zu blocks (", what, k.blocks.size());
    for (std::size_t b = 0; b < k.blocks.size(); ++b)
        std::printf("%s%zu", b ? ", " : "", k.blockSizes[b]);
    std::printf(")\n");
    for (const KinematicFault& f : k.faults)
        std::printf(
            "  %zu|%zu: dip %.1f toward %.0f at (%.3g, %.3g, %.3g), %zu midpoints, rms %.2f d, "
            "slip %.2f d, width %.1f d%s\n",
            f.blockA, f.blockB, f.plane.orientation.dip, f.plane.orientation.dipDirection,
            f.plane.centroid[0], f.plane.centroid[1], f.plane.centroid[2], f.midpoints,
            f.rms / k.meanDiameter, f.slip / k.meanDiameter, f.width / k.meanDiameter,
            f.identifiable ? "" : " (not identifiable)");
}

std::vector<KinematicFault> identifiable(const KinematicResult& k) {
    std::vector<KinematicFault> out;
    for (const auto& f : k.faults)
        if (f.identifiable)
            out.push_back(f);
    return out;
}

} // namespace

// The LAMMPS graben (examples/lammps/in.extension): three blocks (two footwalls, the graben)
// between the last two frames, and the two normal faults between them, dipping about 55 degrees
// towards each other; the graben's floor between the faults' feet near x = 31.
TEST(KinematicFaults, TheLammpsGrabenIsThreeBlocksAndTwoNormalFaults) {
    auto ds = Dataset::open({realRunFile("lammps/dump.extension.gz")});
    for (auto [a, b] : {std::pair<std::size_t, std::size_t>{3, 4}, {2, 4}}) {
        const KinematicResult k = kinematicFaults(*ds->frame(a), *ds->frame(b));
        print(("LAMMPS extension " + std::to_string(a) + " -> " + std::to_string(b)).c_str(), k);
        ASSERT_EQ(k.blocks.size(), 3u);
        const auto faults = identifiable(k);
        ASSERT_EQ(faults.size(), 2u);
        const KinematicFault& east =
            faults[0].plane.orientation.dipDirection < 180 ? faults[0] : faults[1];
        const KinematicFault& west = &east == &faults[0] ? faults[1] : faults[0];
        EXPECT_NEAR(east.plane.orientation.dipDirection, 90, 3);
        EXPECT_NEAR(west.plane.orientation.dipDirection, 270, 3);
        EXPECT_NEAR(east.plane.orientation.dip, 56, 3);
        EXPECT_NEAR(west.plane.orientation.dip, 56, 3);
        // On the README's lines: left x = 33.0 - 0.64 z, right 30.8 + 0.64 z (within 2 d).
        const Vec3d& ce = east.plane.centroid;
        const Vec3d& cw = west.plane.centroid;
        EXPECT_NEAR(ce[0], 33.0 - 0.64 * ce[2], 2.0 / std::sin(std::atan(1 / 0.64)));
        EXPECT_NEAR(cw[0], 30.8 + 0.64 * cw[2], 2.0 / std::sin(std::atan(1 / 0.64)));
        EXPECT_LT(east.rms, 1.0 * k.meanDiameter);
    }
}

// Yade's bonded shear box (examples/yade/shear_box.py): the two grips and what sticks to them
// move as two blocks; between them one gently dipping shear band.
TEST(KinematicFaults, TheYadeShearBoxIsTwoBlocksAndOneBand) {
    auto ds = Dataset::open({realRunFile("yade/shear-spheres-*.vtk")});
    ASSERT_EQ(ds->frameCount(), 3u);
    const KinematicResult k = kinematicFaults(*ds->frame(1), *ds->frame(2));
    print("Yade shear box 1 -> 2", k);
    const auto faults = identifiable(k);
    ASSERT_EQ(faults.size(), 1u);
    EXPECT_NEAR(faults[0].plane.orientation.dip, 10, 4);
}

// The larger shear box (BIG=1 yade -n -x shear_box.py: 6,310 grains, 24 mm high, walls on both y
// faces), its last two snapshots (4 % to 6 % shear): the grips and what sticks to them move as two
// blocks, and between them one shear band dips 22 degrees east (the way the top grip moves: from
// under its trailing end down to the bottom grip's far end), its motion changing within 3.5
// diameters. (Between the snapshots before, 2 % to 4 %, the same band, 21.6 degrees, still changes
// over 5.6 diameters: not yet identifiable.)
TEST(KinematicFaults, TheLargerYadeShearBoxIsTwoBlocksAndOneBand) {
    auto ds = Dataset::open({realRunFile("yade/shearbig-spheres-*.vtk.gz")});
    ASSERT_EQ(ds->frameCount(), 2u);
    const KinematicResult k = kinematicFaults(*ds->frame(0), *ds->frame(1));
    print("Yade larger shear box 2 -> 3", k);
    ASSERT_EQ(k.blocks.size(), 2u);
    const auto faults = identifiable(k);
    ASSERT_EQ(faults.size(), 1u);
    EXPECT_NEAR(faults[0].plane.orientation.dip, 22, 3);
    EXPECT_NEAR(faults[0].plane.orientation.dipDirection, 90, 3);
    EXPECT_LT(faults[0].width, 4.0 * k.meanDiameter);
}

// LIGGGHTS' shortening (examples/liggghts/in.shortening) thickens a wedge in front of the
// pusher diffusely: no boundary between rigid blocks there is a fault by the rules above.
TEST(KinematicFaults, TheLiggghtsWedgeHasNoSharpFault) {
    auto ds = Dataset::open({realRunFile("liggghts/run.dump.gz")});
    const KinematicResult k = kinematicFaults(*ds->frame(2), *ds->frame(3));
    print("LIGGGHTS shortening 2 -> 3", k);
    EXPECT_TRUE(identifiable(k).empty());
}

TEST(KinematicFaults, OneRigidBodyHasNoFaultAndTooFewSpheresAreRefused) {
    auto ds = Dataset::open({realRunFile("lammps/dump.extension.gz")});
    const KinematicResult same = kinematicFaults(*ds->frame(4), *ds->frame(4));
    EXPECT_TRUE(same.faults.empty());
    Frame tiny;
    tiny.ids = {1, 2};
    tiny.x = tiny.y = tiny.z = {0, 1};
    tiny.radius = {0.5f, 0.5f};
    tiny.finalize();
    EXPECT_THROW(kinematicFaults(tiny, tiny), std::invalid_argument);
}

// The LAMMPS shortening run (examples/lammps/in.shortening): a wall pushes sand against a fixed
// one; between the kept frames 1 and 2 (3 to 6 diameters of push) the wedge rides up a thrust
// dipping about 35 degrees towards the pusher (west) over the resting foreland. Later pairs
// deform the wedge internally: no sharp boundary there.
TEST(KinematicFaults, TheLammpsShorteningFormsAThrust) {
    auto ds = Dataset::open({realRunFile("lammps/dump.shortening.gz")});
    ASSERT_EQ(ds->frameCount(), 5u);
    const KinematicResult k = kinematicFaults(*ds->frame(1), *ds->frame(2));
    print("LAMMPS shortening 1 -> 2", k);
    const auto faults = identifiable(k);
    ASSERT_EQ(faults.size(), 1u);
    EXPECT_NEAR(faults[0].plane.orientation.dip, 35, 4);
    EXPECT_NEAR(faults[0].plane.orientation.dipDirection, 270, 5);
    EXPECT_NEAR(faults[0].plane.centroid[0], 22.9, 3.0);
}
