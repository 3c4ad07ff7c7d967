// Issue 37: files written by the DEM programs themselves (tests/data/real_runs/README.md says
// which program, version and script wrote each): LIGGGHTS 3.8.0 (dump custom/vtk with its
// bounding boxes beside the frames, and a text dump), Yade 2023.02a (VTKExporter, export.text,
// export.textExt with attributes). Each reads as the program meant it.
#include "core/data/dataset.hpp"
#include "core/motion/strain_from_motion.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/session.hpp"
#include "core/surface/fault_surface.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

using namespace faultline::core;

namespace {

using faultline::test::realRunFile;

} // namespace

TEST(RealRuns, LiggghtsCustomVtkSeriesSkipsItsBoundingBoxes) {
    auto ds = Dataset::open({realRunFile("liggghts/run_*.vtk")});
    ASSERT_EQ(ds->frameCount(), 4u); // not 6: run_boundingBox_*.vtk are no frames
    EXPECT_EQ(ds->location(0).timestep, 0);
    EXPECT_EQ(ds->location(3).timestep, 60000);
    const auto last = ds->frame(3);
    EXPECT_EQ(last->size(), 2500u);
    EXPECT_FALSE(last->idsAreRowNumbers);
    EXPECT_FALSE(last->radiusIsDefault);
    EXPECT_NE(last->attribute("v_x"), nullptr);
    // LIGGGHTS wrote run_boundingBox_N.vtk for the first and last frames kept here: their box.
    for (std::size_t k : {std::size_t(0), std::size_t(3)}) {
        const SimulationBox& b = ds->frame(k)->box;
        EXPECT_TRUE(b.known) << "frame " << k;
        EXPECT_EQ(b.lo, (std::array<double, 3>{-0.002, -0.0005, -0.0005}));
        EXPECT_EQ(b.hi, (std::array<double, 3>{0.082, 0.0125, 0.0505}));
    }
    EXPECT_FALSE(ds->frame(1)->box.known);
    // The same run as a text dump (gzipped after the run: Debian's LIGGGHTS writes no .gz)
    // agrees sphere by sphere, matched by id (custom/vtk reorders them every frame).
    auto dump = Dataset::open({realRunFile("liggghts/run.dump.gz")});
    ASSERT_EQ(dump->frameCount(), 4u);
    const auto text = dump->frame(3);
    ASSERT_EQ(text->size(), last->size());
    for (std::size_t i = 0; i < text->size(); i += 97) {
        const auto row = last->rowOf(text->ids[i]);
        ASSERT_TRUE(row.has_value());
        EXPECT_NEAR(text->x[i], last->x[*row], 1e-6);
        EXPECT_NEAR(text->radius[i], last->radius[*row], 1e-7);
    }
}

TEST(RealRuns, YadeExportsKeepTheirColumns) {
    // VTKExporter: no cells, ids as doubles, vectors split into _x _y _z.
    auto vtk = Dataset::open({realRunFile("yade/shear-spheres-*.vtk")});
    ASSERT_EQ(vtk->frameCount(), 3u);
    EXPECT_EQ(vtk->location(2).timestep, 2); // the number in the file name
    const auto f = vtk->frame(2);
    EXPECT_EQ(f->size(), 1051u);
    EXPECT_FALSE(f->idsAreRowNumbers);
    EXPECT_NE(f->attribute("velocity_x"), nullptr);
    EXPECT_NE(f->attribute("nbonds"), nullptr);
    // export.text: '#format x_y_z_r', no ids.
    auto text = Dataset::open({realRunFile("yade/shear_xyzr_2.txt")});
    EXPECT_EQ(text->frame(0)->size(), 1051u);
    EXPECT_TRUE(text->frame(0)->idsAreRowNumbers);
    // export.textExt(format='x_y_z_r_attrs') with a comment naming the columns: the names are
    // the comment's; 'id' is the id.
    auto ext = Dataset::open({realRunFile("yade/shear_attrs_2.txt")});
    const auto g = ext->frame(0);
    EXPECT_EQ(g->size(), 1051u);
    EXPECT_FALSE(g->idsAreRowNumbers);
    EXPECT_EQ(g->attributeNames(),
              (std::vector<std::string>{"vx", "vy", "vz", "dx", "dy", "dz", "nbonds"}));
    // The same spheres as the VTK export, by id.
    for (std::size_t i = 0; i < g->size(); i += 53) {
        const auto row = f->rowOf(g->ids[i]);
        ASSERT_TRUE(row.has_value());
        EXPECT_NEAR(g->z[i], f->z[*row], 1e-7);
    }
}

// The Yade run breaks bonds along an inclined band: the spheres that lost bonds gather where the
// shear strain from motion (against the first export) is highest.
TEST(RealRuns, YadeBrokenBondsAreWhereStrainFromMotionIsHigh) {
    auto vtk = Dataset::open({realRunFile("yade/shear-spheres-*.vtk")});
    const auto first = vtk->frame(0), last = vtk->frame(2);
    const auto cols = strainFromMotion(*last, *first, 0);
    const AttributeColumn* before = first->attribute("nbonds");
    const AttributeColumn* after = last->attribute("nbonds");
    ASSERT_NE(before, nullptr);
    ASSERT_NE(after, nullptr);
    // Spheres that lost a bond, among all and among the top tenth by shear strain.
    std::vector<std::pair<float, bool>> byStrain;
    for (std::size_t i = 0; i < last->size(); ++i) {
        const auto r = first->rowOf(last->ids[i]);
        const float s = cols[0].floats[i];
        if (r && !std::isnan(s))
            byStrain.push_back({s, after->value(i) < before->value(*r)});
    }
    std::sort(byStrain.begin(), byStrain.end(), [](auto a, auto b) { return a.first > b.first; });
    const std::size_t top = byStrain.size() / 10;
    const double all =
        double(std::count_if(byStrain.begin(), byStrain.end(), [](auto p) { return p.second; })) /
        double(byStrain.size());
    const double inTop = double(std::count_if(byStrain.begin(), byStrain.begin() + long(top),
                                              [](auto p) { return p.second; })) /
                         double(top);
    std::printf("broken-bond spheres: %.3f of all, %.3f of the top tenth by shear strain\n", all,
                inTop);
    // Measured: 0.31 of all spheres, 0.53 of the top tenth (bonds break in a band a few grains
    // thick, but 31% of this small sample touch a broken bond).
    EXPECT_GT(inTop, 1.5 * all);
}

// Issue 36: a real LAMMPS run (examples/lammps/in.extension, Debian's LAMMPS 29 Sep 2021) of
// sand stretched over a basal velocity discontinuity, written as id x y z radius only. The
// incremental shear strain from motion (against 4 run frames before, one frame here) picks out
// the graben's two normal faults: the run's own fault lines (fitted to the strain peaks per
// depth by tests/data/real_runs/lammps/README.md, dips about 57 degrees) hold the high-strain
// grains, the footwalls stay quiet. y is periodic, wrapped without image flags.
TEST(RealRuns, LammpsExtensionIncrementalStrainPicksOutTheGrabenFaults) {
    auto ds = Dataset::open({realRunFile("lammps/dump.extension.gz")});
    ASSERT_EQ(ds->frameCount(), 5u);
    ds->setStrains({StrainSpec{true, -1, 0, "inc_"}});
    const auto last = ds->frame(4);
    ASSERT_EQ(last->size(), 7533u);
    EXPECT_TRUE(last->box.periodic[1]);
    const AttributeColumn* shear = last->attribute("inc_shear_strain");
    ASSERT_NE(shear, nullptr);
    // Distance of a grain to the nearer fault line: left x = 33.0 - 0.64 z, right 30.8 + 0.64 z
    // (measured along x, times the sine of the dip for the distance to the plane).
    const double s = std::sin(std::atan(1.0 / 0.64));
    auto toFault = [&](std::size_t i) {
        const double x = last->x[i], z = last->z[i];
        return std::min(std::fabs(x - (33.0 - 0.64 * z)), std::fabs(x - (30.8 + 0.64 * z))) * s;
    };
    auto inFootwall = [&](std::size_t i) {
        const double x = last->x[i], z = last->z[i];
        return (x < 33.0 - 0.64 * z - 4 / s) || (x > 30.8 + 0.64 * z + 4 / s);
    };
    std::vector<float> band, footwall;
    std::vector<std::pair<float, std::size_t>> ranked;
    std::size_t nan = 0;
    for (std::size_t i = 0; i < last->size(); ++i) {
        const float v = shear->floats[i];
        if (std::isnan(v)) {
            ++nan;
            continue;
        }
        ranked.push_back({v, i});
        if (last->z[i] > 2.5 && toFault(i) < 1.5)
            band.push_back(v);
        else if (inFootwall(i))
            footwall.push_back(v);
    }
    EXPECT_LT(nan, last->size() / 100); // only grains with too few neighbours
    auto median = [](std::vector<float> v) {
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return double(v[v.size() / 2]);
    };
    ASSERT_GT(band.size(), 300u);
    ASSERT_GT(footwall.size(), 2000u);
    const double inBand = median(band), outside = median(footwall);
    std::printf("median inc_shear_strain: %.4f in the bands, %.4f in the footwalls\n", inBand,
                outside);
    EXPECT_GT(inBand, 50 * outside);
    // The top tenth of the grains by strain lie on the faults.
    std::sort(ranked.begin(), ranked.end(), std::greater<>());
    const std::size_t top = ranked.size() / 10;
    std::size_t near = 0;
    for (std::size_t k = 0; k < top; ++k)
        near += toFault(ranked[k].second) < 3.0 ? 1 : 0;
    std::printf("top tenth within 3 of a fault: %.2f\n", double(near) / double(top));
    EXPECT_GT(double(near) / double(top), 0.8);
    // Frame 0 has no frame before it: no values, none passes a threshold.
    EXPECT_TRUE(std::isnan(ds->frame(0)->attribute("inc_shear_strain")->floats[0]));
}

// Issue 37: through time on the real LAMMPS run. Candidates of the last frame's incremental
// strain, followed back: both graben faults appear in frame 1 (the run's timestep 50000, the
// first with a frame before it) and their throw, measured from strain from motion's reference
// positions since frame 0 (the dump has no x0, y0, z0), grows in every frame (normal faults:
// negative throw).
TEST(RealRuns, TheLammpsGrabenFaultsAppearAndTheirThrowGrows) {
    faultline::test::TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {realRunFile("lammps/dump.extension.gz")}}});
    s.apply({{"op", "frame.set"}, {"frame", 4}});
    s.apply({{"op", "strain.add"}, {"since_offset", -1}, {"prefix", "inc_"}});
    s.apply({{"op", "strain.add"}, {"since_frame", 0}});
    s.apply(
        {{"op", "threshold.add"}, {"variable", "inc_shear_strain"}, {"low", 0.15}, {"high", 1e30}});
    s.apply({{"op", "fault.candidates"}, {"min_size", 50}, {"prefix", "F"}});
    ASSERT_EQ(s.state().faults.size(), 2u);
    // Reference positions are variables: where each grain was in frame 0 (y across the periodic
    // boundary as the minimum image next to where it is now).
    const auto now = s.currentFrame();
    const auto first = s.dataset()->frame(0);
    for (std::size_t i = 0; i < now->size(); i += 97) {
        const std::size_t r = *first->rowOf(now->ids[i]);
        EXPECT_NEAR(now->attribute("ref_x")->floats[i], first->x[r], 1e-3);
        EXPECT_NEAR(now->attribute("ref_z")->floats[i], first->z[r], 1e-3);
        const double dy = std::fabs(now->attribute("ref_y")->floats[i] - first->y[r]);
        EXPECT_TRUE(dy < 1e-3 || std::fabs(dy - 6.0) < 1e-3) << dy;
    }
    s.apply({{"op", "export.csv"}, {"what", "fault_events"}, {"path", dir.file("events.csv")}});
    s.apply({{"op", "export.csv"}, {"what", "fault_growth"}, {"path", dir.file("growth.csv")}});
    EXPECT_EQ(faultline::test::slurp(dir.file("events.csv")),
              "frame,kind,faults\n1,appeared,F1\n1,appeared,F2\n");
    // growth: frame,fault,count,dip,dip_direction,strike,thickness,area,throw,...
    std::istringstream growth(faultline::test::slurp(dir.file("growth.csv")));
    std::string line;
    std::getline(growth, line);
    std::map<std::string, std::vector<double>> throws;
    while (std::getline(growth, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');)
            f.push_back(c);
        if (std::stoi(f[0]) >= 1)
            throws[f[1]].push_back(std::stod(f[8]));
    }
    for (const auto& [fault, t] : throws) {
        ASSERT_EQ(t.size(), 4u) << fault;
        std::printf("%s throw by frame: %.2f %.2f %.2f %.2f\n", fault.c_str(), t[0], t[1], t[2],
                    t[3]);
        for (std::size_t k = 1; k < t.size(); ++k)
            EXPECT_LT(t[k], t[k - 1] - 0.5) << fault << " frame " << k + 1;
        EXPECT_LT(t.back(), -3.5); // the plate moved 8 grain diameters in all
    }
}

// A journal's surface.set for the graben's bands (no iso-value; the default inverse-square
// kernel) wraps the bands' spheres: it drew one ball around the whole block while it kept the
// default iso-value of 1, far outside the summed field of about 2,000 spheres.
TEST(RealRuns, ANewSurfaceOfTheLammpsGrabenBandsWrapsThem) {
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {realRunFile("lammps/dump.extension.gz")}}});
    s.apply({{"op", "frame.set"}, {"frame", 4}});
    s.apply({{"op", "strain.add"}, {"since_offset", -1}, {"prefix", "inc_"}});
    s.apply(
        {{"op", "threshold.add"}, {"variable", "inc_shear_strain"}, {"low", 0.05}, {"high", 1e30}});
    s.apply({{"op", "fault.create"}, {"name", "F1"}, {"from", "visible"}});
    s.apply({{"op", "threshold.set"}, {"variable", "inc_shear_strain"}, {"enabled", false}});
    const std::size_t members = s.state().fault("F1")->ids.size();
    EXPECT_GT(members, 1000u);
    s.apply({{"op", "surface.set"}, {"fault", "F1"}, {"color_by", "inc_shear_strain"}});
    const SurfaceSettings& st = *s.state().surface("F1");
    EXPECT_EQ(st.iso, *faultWrappingIso(*s.currentFrame(), *s.state().fault("F1"), st));
    EXPECT_GT(st.iso, 5.0);
    // The surface lies around the bands' spheres: within a few diameters of their bounds.
    const FaultSurfaceRequest request = surfaceRequestFor(s, "F1", "test");
    const SurfaceResult built = buildFaultSurface(*s.currentFrame(), request);
    ASSERT_GT(built.mesh.triangleCount(), 0u);
    const auto frame = s.currentFrame();
    std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (std::int64_t id : s.state().fault("F1")->ids) {
        const std::size_t r = *frame->rowOf(id);
        const float c[3] = {frame->x[r], frame->y[r], frame->z[r]};
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
    }
    for (const auto& p : built.mesh.positions)
        for (int k = 0; k < 3; ++k) {
            ASSERT_GT(p[k], lo[k] - 3.0f) << "axis " << k;
            ASSERT_LT(p[k], hi[k] + 3.0f) << "axis " << k;
        }
}
