// Issue 37: fault candidates on real DEM runs, checked against kinematic truth
// (kinematic_faults.hpp). Thresholds on the incremental shear strain from motion at several
// percentiles between the 85th and the 95th: every identifiable kinematic fault must be its own
// candidate, with dip within 5 degrees, dip direction within 15 and centroid within 2 mean
// diameters of the truth plane, and no candidate may hold two of them.
#include "core/data/dataset.hpp"
#include "core/faults/candidates.hpp"
#include "core/faults/metrics.hpp"
#include "core/motion/kinematic_faults.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace faultline::core;

namespace {

using faultline::test::realRunFile;

double angleBetween(double a, double b) {
    const double d = std::fmod(std::fabs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// Issue 37's match: dip within 5 degrees, dip direction within 15, centroid within 2 mean
// diameters of the truth plane.
constexpr double kMaxDipError = 5.0, kMaxDirError = 15.0, kMaxDistance = 2.0;

struct Match {
    std::size_t candidate = 0;
    double dipError = 0, dirError = 0, distance = 0; // distance in mean diameters
    std::size_t size = 0;
    // Against the truth over the part of the fault the candidate spans (the kinematic
    // midpoints within the candidate's down-dip range): a curved fault of which only the deep
    // part strains in an increment is matched against that part's dip.
    double localDip = NAN, localDipError = 90, localDirError = 180;
    double truthDipDirection = 0;
};

// The truth plane refitted through its midpoints that lie within the down-dip span (10th to
// 90th percentile) of the candidate's members; invalid when fewer than 30 are left.
PlaneFit localTruth(const KinematicResult& truth, const KinematicFault& f, const Frame& after,
                    const Fault& candidate) {
    const Vec3d down = downDipVector(f.plane.normal);
    auto along = [&](const Vec3d& p) {
        return (p[0] - f.plane.centroid[0]) * down[0] + (p[1] - f.plane.centroid[1]) * down[1] +
               (p[2] - f.plane.centroid[2]) * down[2];
    };
    std::vector<double> span;
    for (std::int64_t id : candidate.ids)
        if (auto row = after.rowOf(id))
            span.push_back(along({after.x[*row], after.y[*row], after.z[*row]}));
    if (span.size() < 3)
        return {};
    std::sort(span.begin(), span.end());
    const double lo = span[span.size() / 10], hi = span[span.size() * 9 / 10];
    std::vector<Vec3d> within;
    for (const Vec3d& p : f.points)
        if (const double s = along(p); s >= lo && s <= hi)
            within.push_back(p);
    return within.size() >= 30 ? fitPlane(within, truth.sectionAxis) : PlaneFit{};
}

// Each identifiable kinematic fault of before -> after against the candidates of `after`'s
// spheres whose `variable` is at least its `percentile`. Prints a line per fault.
std::vector<Match> check(const char* name, const Frame& before, const Frame& after,
                         const std::string& variable, double percentile, std::size_t minSize,
                         std::size_t* candidateCount = nullptr) {
    const KinematicResult truth = kinematicFaults(before, after);
    const AttributeColumn* column = after.attribute(variable);
    std::vector<float> values;
    for (std::size_t i = 0; i < after.size(); ++i)
        if (std::isfinite(column->floats[i]))
            values.push_back(column->floats[i]);
    std::sort(values.begin(), values.end());
    const float low = values[std::size_t(percentile / 100.0 * double(values.size() - 1))];
    std::vector<std::uint8_t> visible(after.size(), 0);
    for (std::size_t i = 0; i < after.size(); ++i)
        visible[i] = column->floats[i] >= low;
    CandidateOptions options;
    options.minSize = minSize;
    const CandidateSet set = findCandidates(after, visible, options);
    const std::vector<Fault> faults = faultsFromCandidates(set.candidates, "C");
    MetricsOptions mo;
    mo.computeThrow = false;
    const auto metrics = computeFrameMetrics(after, 0, faults, mo);
    std::vector<Match> out;
    if (candidateCount)
        *candidateCount = faults.size();
    std::printf("%s, p%.1f (%s >= %.4g): %zu candidates\n", name, percentile, variable.c_str(), low,
                faults.size());
    for (const KinematicFault& f : truth.faults) {
        if (!f.identifiable)
            continue;
        // The candidate whose centroid lies nearest the truth plane, among those whose
        // members are mostly within 4 diameters of it.
        Match best;
        best.distance = INFINITY;
        for (std::size_t c = 0; c < metrics.size(); ++c) {
            const FaultFrameMetrics& m = metrics[c];
            if (!m.planeValid)
                continue;
            std::size_t near = 0, total = 0;
            for (std::int64_t id : faults[c].ids)
                if (auto row = after.rowOf(id)) {
                    const Vec3d q{after.x[*row] - f.plane.centroid[0],
                                  after.y[*row] - f.plane.centroid[1],
                                  after.z[*row] - f.plane.centroid[2]};
                    const double s = q[0] * f.plane.normal[0] + q[2] * f.plane.normal[2] +
                                     q[1] * f.plane.normal[1];
                    near += std::fabs(s) < 4 * truth.meanDiameter;
                    ++total;
                }
            if (near * 2 < total)
                continue;
            const Vec3d q{m.centroid[0] - f.plane.centroid[0], m.centroid[1] - f.plane.centroid[1],
                          m.centroid[2] - f.plane.centroid[2]};
            const double dist = std::fabs(q[0] * f.plane.normal[0] + q[1] * f.plane.normal[1] +
                                          q[2] * f.plane.normal[2]) /
                                truth.meanDiameter;
            const double score = dist + angleBetween(m.dip, f.plane.orientation.dip) / 5.0;
            if (score < best.distance + best.dipError / 5.0 || std::isinf(best.distance))
                best = {c, std::fabs(m.dip - f.plane.orientation.dip),
                        angleBetween(m.dipDirection, f.plane.orientation.dipDirection), dist,
                        faults[c].ids.size()};
        }
        if (std::isinf(best.distance)) {
            std::printf("  truth dip %.1f/%03.0f: no candidate\n", f.plane.orientation.dip,
                        f.plane.orientation.dipDirection);
            best.dipError = 90;
        } else {
            const FaultFrameMetrics& m = metrics[best.candidate];
            if (const PlaneFit local = localTruth(truth, f, after, faults[best.candidate]);
                local.valid) {
                best.localDip = local.orientation.dip;
                best.localDipError = std::fabs(m.dip - local.orientation.dip);
                best.localDirError = angleBetween(m.dipDirection, local.orientation.dipDirection);
            }
            // The verdict on the unrounded errors (scripts/candidate-matches.py reads it).
            const bool within = best.dipError <= kMaxDipError && best.dirError <= kMaxDirError &&
                                best.distance <= kMaxDistance;
            std::printf(
                "  truth dip %.1f/%03.0f: C%zu (%zu spheres) dip %.1f/%03.0f, errors %.1f / %.1f "
                "degrees, %.2f d from the plane; over its span the truth dips %.1f (error %.1f); "
                "%s\n",
                f.plane.orientation.dip, f.plane.orientation.dipDirection, best.candidate + 1,
                best.size, m.dip, m.dipDirection, best.dipError, best.dirError, best.distance,
                best.localDip, best.localDipError, within ? "within" : "outside");
        }
        best.truthDipDirection = f.plane.orientation.dipDirection;
        out.push_back(best);
    }
    return out;
}

void expectMatched(const std::vector<Match>& matches, std::size_t faults) {
    ASSERT_EQ(matches.size(), faults);
    for (std::size_t i = 0; i < matches.size(); ++i) {
        EXPECT_LE(matches[i].dipError, kMaxDipError);
        EXPECT_LE(matches[i].dirError, kMaxDirError);
        EXPECT_LE(matches[i].distance, kMaxDistance);
        for (std::size_t j = 0; j < i; ++j)
            EXPECT_NE(matches[i].candidate, matches[j].candidate) << "two faults in one candidate";
    }
}

// Two faults, each its own candidate, within `maxDipError` of dip, 15 degrees of dip direction
// and 2 diameters.
void expectTwoApart(const std::vector<Match>& matches, double maxDipError) {
    ASSERT_EQ(matches.size(), 2u);
    EXPECT_NE(matches[0].candidate, matches[1].candidate) << "the V came out as one candidate";
    for (const Match& m : matches) {
        EXPECT_LE(m.dipError, maxDipError);
        EXPECT_LE(m.dirError, kMaxDirError);
        EXPECT_LE(m.distance, kMaxDistance);
    }
}

} // namespace

// The graben's two faults each their own candidate, within 5 degrees of dip, 15 of dip direction
// and 2 diameters, at every whole percentile from the 85th to the 90th. The faults are curved
// (steeper at depth, flatter near the surface: the truth planes' midpoints lie up to 1.5 d off a
// plane), and above the 90th only their deep parts strain enough in this increment: the right
// fault's candidate is its deep half, 6.9 degrees steeper than the whole fault's plane at the
// 92.5th and 10.6 at the 95th. Against the truth over the part each candidate spans it is 1.6
// degrees off at the 92.5th (asserted) and 5.9 at the 95th (printed, not asserted: issue 37's
// closing note). (At the 90th the right fault's candidate was its deep half, 195 spheres 5.3
// degrees off among three candidates, until leftovers went to the nearest surface only after
// step 5 of fault_network.hpp: now 308 spheres, 1.1 degrees off.)
TEST(CandidatesOnRealRuns, TheLammpsGrabensTwoFaultsFrom85To90AndHowFarAbove) {
    auto ds = Dataset::open({realRunFile("lammps/dump.extension.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {85.0, 86.0, 87.0, 88.0, 89.0, 90.0})
        expectMatched(check("LAMMPS extension 3 -> 4", *ds->frame(3), *ds->frame(4),
                            "inc_shear_strain", p, 50),
                      2);
    for (double p : {92.5, 95.0}) {
        const auto above = check("LAMMPS extension 3 -> 4", *ds->frame(3), *ds->frame(4),
                                 "inc_shear_strain", p, 50);
        expectTwoApart(above, 12.0);
        for (const Match& m : above)
            if (p < 95) {
                EXPECT_LE(m.localDipError, 5.0) << "against the truth over the candidate's span";
            }
    }
}

// One increment earlier (frames 2 -> 3) both graben faults slip along their whole length: each
// its own candidate within 5 degrees, 15 of dip direction and 2 diameters from the 85th to the
// 95th percentile. At the 92nd and 92.5th the west-dipping fault's middle strains less than the
// threshold: its steep deep part and its flatter shallow part, 18 degrees apart, were two
// candidates; joined as one bent fault (their planes meet between them), there are two
// candidates for the two faults. (At the 90.5th and 92nd the faults' shallow ends drop out and
// the steeper rest is 5.1 to 5.3 degrees off the whole fault's plane: printed, not asserted.)
TEST(CandidatesOnRealRuns, TheLammpsGrabensFaultsWhileBothSlipAndABentFaultAsOne) {
    auto ds = Dataset::open({realRunFile("lammps/dump.extension.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {85.0, 87.5, 90.0, 92.5, 95.0})
        expectMatched(check("LAMMPS extension 2 -> 3", *ds->frame(2), *ds->frame(3),
                            "inc_shear_strain", p, 50),
                      2);
    for (double p : {92.0, 92.5}) {
        std::size_t count = 0;
        const auto matches = check("LAMMPS extension 2 -> 3", *ds->frame(2), *ds->frame(3),
                                   "inc_shear_strain", p, 50, &count);
        EXPECT_EQ(count, 2u) << "a fault in two candidates at the " << p << "th percentile";
        ASSERT_EQ(matches.size(), 2u);
        EXPECT_NE(matches[0].candidate, matches[1].candidate);
    }
}

// Yade's shear band is 2.5 grains thick in a layer under 7 grains high, with 1051 grains in all:
// at the 85th percentile it is one candidate of 75 spheres, 10 degrees steeper than the
// kinematic band (its free end); above that the strained grains stand apart in fragments. Printed
// for the closing note; asserted only that the 85th gives the band's candidate on its plane.
// (The box is the readers' fixture; the larger one below holds a band apart from its grips.)
TEST(CandidatesOnRealRuns, TheYadeShearBandIsOneCandidateAtThe85th) {
    auto ds = Dataset::open({realRunFile("yade/shear-spheres-*.vtk")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    const auto at85 =
        check("Yade shear box 1 -> 2", *ds->frame(1), *ds->frame(2), "inc_shear_strain", 85, 15);
    ASSERT_EQ(at85.size(), 1u);
    EXPECT_LE(at85[0].distance, 2.0);
    EXPECT_LE(at85[0].dirError, 15.0);
    for (double p : {90.0, 95.0})
        check("Yade shear box 1 -> 2", *ds->frame(1), *ds->frame(2), "inc_shear_strain", p, 15);
}

// The larger shear box (examples/yade/shear_box.py with BIG=1: 6,310 grains, 20 diameters between
// the grips), 4 % to 6 % shear: one band dipping 22 degrees east (kinematic_faults_test.cpp), three
// to five grains thick and built of three segments: 28-32 degrees under the top grip's trailing
// end, nearly flat in the middle (0-9 degrees), 17-28 near the far end (like the Riedel shears of
// a shear box of sand). From the 85th to the 88th percentile the segments touch and the band is
// one candidate, within 0.6 degrees and 0.2 diameters of the kinematic band (step 8 of
// fault_network.hpp: each segment was a candidate of its own, the one matched up to 4.6 degrees
// off). Above that the segments stand apart, and the one nearest the band's plane is within 5
// degrees, 15 of dip direction and 2 diameters up to the 93rd (measured: at most 2.2 degrees).
// At the 94th and 95th what is left of the outer segments is their steeper part: 6.1 and 7.2
// degrees off (printed, not asserted).
TEST(CandidatesOnRealRuns, TheLargerYadeShearBoxBandFrom85To93) {
    auto ds = Dataset::open({realRunFile("yade/shearbig-spheres-*.vtk.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {85.0, 86.0, 87.0, 87.5, 88.0, 89.0, 90.0, 91.0, 92.0, 92.5, 93.0}) {
        std::size_t count = 0;
        const auto matches = check("Yade larger shear box 2 -> 3", *ds->frame(0), *ds->frame(1),
                                   "inc_shear_strain", p, 30, &count);
        expectMatched(matches, 1);
        if (p <= 88) {
            EXPECT_EQ(count, 1u) << "the band in pieces at the " << p << "th percentile";
            ASSERT_EQ(matches.size(), 1u);
            EXPECT_LE(matches[0].dipError, 1.0);
        }
        EXPECT_LE(count, 3u) << "the band in more pieces than its segments";
    }
    for (double p : {94.0, 95.0})
        check("Yade larger shear box 2 -> 3", *ds->frame(0), *ds->frame(1), "inc_shear_strain", p,
              30);
}

// The shortening run's thrust (kinematic_faults_test.cpp: 35 degrees towards the pusher) is
// one candidate within 5 degrees and 2 diameters at every threshold from the 85th to the 95th
// percentile of frame 2's incremental strain (measured: at most 2.7 degrees and 0.33 d off).
TEST(CandidatesOnRealRuns, TheLammpsShorteningThrustFrom85To95) {
    auto ds = Dataset::open({realRunFile("lammps/dump.shortening.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {85.0, 87.0, 89.0, 90.0, 92.5, 95.0})
        expectMatched(check("LAMMPS shortening 1 -> 2", *ds->frame(1), *ds->frame(2),
                            "inc_shear_strain", p, 50),
                      1);
}

// Yade's bonded sandbox (examples/yade/sandbox_extension.py: 5,851 grains, bonds of 2000 Pa)
// stretched over the edge of its fixed half. In the first millimetre of pull (frames 0 -> 1) one
// normal fault dips 62 degrees west over the edge, a band 4-8 grains thick that widens at depth:
// one candidate within 5 degrees, 15 of dip direction and 2 diameters at every threshold from
// the 85th to the 95th percentile (measured: at most 2.5 degrees and 0.4 d off). From the 86th
// to the 88th the band's deep end lies more than a neighbourhood from the region grown along its
// edge; it was left out of the candidate, whose plane then tilted 6-8 degrees, until the
// nearest-surface rounds (step 6 of fault_network.hpp) repeated while they took spheres.
// In the second millimetre (1 -> 2) a steeper east-dipping fault (78 degrees) joins it in a V
// whose base is a broad zone of distributed strain. Both faults are matched as above at the
// 85th, 86th, 92nd and 93rd percentile, and at every threshold from the 85th to the 95th they
// are two candidates: within 2 diameters and 7 degrees from the 90th up (the base's strained
// grains pull the planes by up to 6.8), within 8 degrees from the 87th to the 89th (printed).
// The base is shared between the two by nearest surface (step 6 of fault_network.hpp, after
// step 5 seeded groups where none reached); before, from the 87th to the 89th it went whole with
// the west-dipping fault, 14-24 degrees off. At the 85th every region grown in the noisy V stays
// below the minimum size, and the faults are found through step 5's seeded groups (4.7 and 2.0
// degrees off), among six candidates: the strained V in pieces, the west fault as its 67 most
// planar spheres.
TEST(CandidatesOnRealRuns, TheYadeSandboxNormalFaults) {
    auto ds = Dataset::open({realRunFile("yade/sb-spheres-*.vtk.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {85.0, 86.0, 87.0, 87.5, 88.0, 89.0, 90.0, 91.0, 92.0, 92.5, 93.0, 94.0, 95.0})
        expectMatched(
            check("Yade sandbox 0 -> 1", *ds->frame(0), *ds->frame(1), "inc_shear_strain", p, 30),
            1);
    for (double p : {85.0, 86.0, 92.0, 93.0})
        expectMatched(
            check("Yade sandbox 1 -> 2", *ds->frame(1), *ds->frame(2), "inc_shear_strain", p, 30),
            2);
    for (double p : {90.0, 91.0, 92.5, 94.0, 95.0}) {
        expectTwoApart(
            check("Yade sandbox 1 -> 2", *ds->frame(1), *ds->frame(2), "inc_shear_strain", p, 30),
            7.0);
    }
    for (double p : {87.0, 88.0, 89.0}) {
        const auto v =
            check("Yade sandbox 1 -> 2", *ds->frame(1), *ds->frame(2), "inc_shear_strain", p, 30);
        ASSERT_EQ(v.size(), 2u);
        EXPECT_NE(v[0].candidate, v[1].candidate) << "the V came out as one candidate";
    }
}

// The same sandbox with a floor under its base (FLOOR=1: the grains over the opening gap stay
// in), frames 2 and 3: a graben, its keystone sinking 0.76 mm between a 55-degree west-dipping
// fault, a band one or two grains thick, and a 75-degree east-dipping zone three to six grains
// thick whose foot holds the V's broad base. The west-dipping fault grows only regions smaller
// than the minimum size; it is found through step 5 of fault_network.hpp (regions where no group
// reached seed groups) and step 7 (planar pieces). Both faults are each their own candidate
// within 5 degrees and 2 diameters at the 87.5th, 90th and 93rd percentile (measured: at most
// 4.6 degrees and 1.8 d), and two candidates from the 87.5th to the 94th. In between, the V's
// base, shared between them by nearest surface (step 6), pulls one of them off: the west fault
// 11.1 and 6.3 degrees steeper at the 91st and 92nd, the east zone 5.4 and 6.2 flatter at the
// 92.5th and 94th. Before step 6 came after step 5, the east zone took the whole base and read
// 12-18 degrees flat from the 87.5th to the 92nd: matched at the 85th and 92.5th only.
// Printed: the 85th (east 5.7 degrees off) and the 95th (what is left of the east zone, 10.3).
TEST(CandidatesOnRealRuns, TheYadeSandboxWithAFloorGrabenFaults) {
    auto ds = Dataset::open({realRunFile("yade/sbfloor-spheres-*.vtk.gz")});
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    for (double p : {87.5, 90.0, 93.0})
        expectMatched(check("Yade sandbox with a floor 2 -> 3", *ds->frame(0), *ds->frame(1),
                            "inc_shear_strain", p, 30),
                      2);
    for (double p : {91.0, 92.0, 92.5, 94.0})
        expectTwoApart(check("Yade sandbox with a floor 2 -> 3", *ds->frame(0), *ds->frame(1),
                             "inc_shear_strain", p, 30),
                       12.0);
    for (double p : {85.0, 95.0})
        check("Yade sandbox with a floor 2 -> 3", *ds->frame(0), *ds->frame(1), "inc_shear_strain",
              p, 30);
}
