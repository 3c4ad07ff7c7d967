#include "core/data/dataset.hpp"
#include "core/synth/dump_writer.hpp"
#include "core/synth/extension_model.hpp"
#include "core/synth/fault_bands.hpp"

#include "test_files.hpp"
#include "tests/common/sanitizers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace faultline::core;
using faultline::test::slurp;

namespace {

// 960 spheres, about 900 steps: a fraction of a second.
ExtensionModelOptions tinyOptions() {
    ExtensionModelOptions o;
    o.columns = 40;
    o.layers = 2;
    o.rows = 12;
    o.settleSteps = 300;
    o.extension = 0.04;
    o.discontinuities = {0.5};
    o.frames = 4;
    return o;
}

std::string runToDump(const faultline::test::TempDir& dir, ExtensionModelOptions o, int threads,
                      const std::string& name) {
    o.threads = threads;
    const std::string path = dir.file(name);
    LammpsDumpWriter w(path, 1);
    runExtensionModel(o, [&](const Frame& f, int) { w.write(f, extensionDumpColumns()); });
    w.close();
    return path;
}

} // namespace

TEST(ExtensionModel, SameSeedGivesIdenticalBytesWhateverTheThreadCount) {
    const faultline::test::TempDir dir;
    const ExtensionModelOptions o = tinyOptions();
    const std::string a = slurp(runToDump(dir, o, 2, "a.lammpstrj.gz"));
    const std::string b = slurp(runToDump(dir, o, 2, "b.lammpstrj.gz"));
    const std::string c = slurp(runToDump(dir, o, 1, "c.lammpstrj.gz"));
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b) << "two runs with the same seed differ";
    EXPECT_TRUE(a == c) << "one thread and two threads differ";
    ExtensionModelOptions other = o;
    other.seed = 2;
    EXPECT_FALSE(a == slurp(runToDump(dir, other, 2, "d.lammpstrj.gz")))
        << "the seed changes nothing";
}

TEST(ExtensionModel, DumpReadsBackWithTheContractColumns) {
    const faultline::test::TempDir dir;
    ExtensionModelOptions o = tinyOptions();
    o.law = BreakingStrainLaw::Weibull;
    const std::string path = runToDump(dir, o, 2, "read.lammpstrj.gz");
    auto ds = Dataset::open({path});
    ASSERT_EQ(ds->frameCount(), 4u);
    const auto first = ds->frame(0);
    ASSERT_EQ(first->size(), 960u);
    EXPECT_EQ(first->attributeNames(), (std::vector<std::string>{"type", "strain", "broken_bonds",
                                                                 "layer", "x0", "y0", "z0"}));
    EXPECT_TRUE(first->box.known);
    // Frame 0 is the settled state: the reference of strain and of x0 y0 z0.
    EXPECT_EQ(first->attribute("strain")->max, 0.0);
    EXPECT_EQ(first->attribute("broken_bonds")->max, 0.0);
    for (std::size_t i = 0; i < first->size(); ++i) {
        EXPECT_EQ(first->x[i], first->attribute("x0")->value(i));
        EXPECT_EQ(first->z[i], first->attribute("z0")->value(i));
    }
    EXPECT_EQ(first->attribute("layer")->min, 0.0);
    EXPECT_EQ(first->attribute("layer")->max, 9.0);
    EXPECT_EQ(first->attribute("type")->min, 1.0);
    EXPECT_EQ(first->attribute("type")->max, 3.0);
    // The right end moved away by the extension: 4% of the 82-radius length.
    const auto last = ds->frame(3);
    EXPECT_NEAR(last->box.hi[0] - first->box.hi[0], 0.04 * 82.0, 1e-3);
    EXPECT_GT(last->attribute("broken_bonds")->max, 0.0);
}

// The two science checks below grow whole models (2,000-2,800 steps): a minute and more under
// ThreadSanitizer, where the generator's threads are what is checked, and the other tests here
// (the same seed, identical bytes whatever the thread count) run the same parallel code.
TEST(ExtensionModel, BrokenBondsGatherInAFewNarrowDippingZones) {
    if (faultline::test::kUnderThreadSanitizer)
        GTEST_SKIP() << "a science check; the generator's threads are checked by the others";
    // 4,800 spheres, two grabens: about 2,800 steps.
    ExtensionModelOptions o;
    o.columns = 100;
    o.layers = 2;
    o.rows = 24;
    o.settleSteps = 600;
    o.frames = 2;
    ExtensionModel model(o);
    model.advance(model.frameStep(1));
    const Frame last = model.snapshot();
    FaultBandOptions bands;
    bands.bands = 4;
    bands.width = 6; // three sphere diameters
    const FaultBandMeasure m = measureFaultBands(last, bands);
    std::ostringstream what;
    what << "damaged share " << m.damagedShare << ", uniform share " << m.uniformShare
         << ", bands:";
    for (const auto& b : m.bands)
        what << " " << b.dip << (b.towardsPlusX > 0 ? "E" : "W");
    SCOPED_TRACE(what.str());
    EXPECT_GT(model.brokenBondCount(), 300u);
    // Most broken bonds lie in four bands six radii wide, which would hold a quarter of them
    // if damage were spread evenly.
    EXPECT_GT(m.damagedShare, 0.6);
    EXPECT_GT(m.concentration(), 2.5);
    // Normal faults of both dip directions, dipping near 60 degrees.
    ASSERT_EQ(m.bands.size(), 4u);
    bool east = false, west = false;
    for (const auto& b : m.bands) {
        EXPECT_GE(b.dip, 50);
        EXPECT_LE(b.dip, 70);
        (b.towardsPlusX > 0 ? east : west) = true;
    }
    EXPECT_TRUE(east && west);
}

TEST(ExtensionModel, ValidateNamesTheBadOption) {
    ExtensionModelOptions o = tinyOptions();
    o.localDamping = 1.5;
    EXPECT_THROW(validate(o), std::invalid_argument);
    o = tinyOptions();
    o.discontinuities = {};
    EXPECT_THROW(validate(o), std::invalid_argument);
    EXPECT_NO_THROW(validate(tinyOptions()));
    EXPECT_NO_THROW(validate(extensionOptionsFor(ModelSize::Large)));
}

TEST(ExtensionModel, SizesHaveTheAdvertisedSphereCounts) {
    auto count = [](ModelSize s) {
        const auto o = extensionOptionsFor(s);
        return o.columns * o.layers * o.rows;
    };
    EXPECT_EQ(count(ModelSize::Medium), 60000);
    EXPECT_EQ(count(ModelSize::Large), 525000);
    EXPECT_LT(count(ModelSize::Small), 20000);
}

TEST(ExtensionModel, TheDemoIsABlockOfTheAdvertisedSize) {
    const ExtensionModelOptions o = extensionDemoOptions();
    EXPECT_NO_THROW(validate(o));
    EXPECT_GE(o.columns * o.layers * o.rows, 200000);
    EXPECT_GE(o.frames, 40);
    // Thinnest side in radii (HCP: 2 per column, 2 sqrt(2/3) per layer, sqrt(3) per row).
    const double sides[3] = {2.0 * o.columns, 2 * std::sqrt(2.0 / 3.0) * o.layers,
                             std::sqrt(3.0) * o.rows};
    EXPECT_GE(*std::min_element(sides, sides + 3), 30.0);
    EXPECT_GT(o.obliquity, 0.0); // faults change place along strike
}

TEST(ExtensionModel, SegmentedDiscontinuitiesMoveTheFaultsAlongStrike) {
    if (faultline::test::kUnderThreadSanitizer)
        GTEST_SKIP() << "a science check; the generator's threads are checked by the others";
    // A small block (11,520 spheres, ~2,000 steps): one discontinuity in two segments 12 radii
    // apart. Broken bonds gather in a few narrow zones, and the zones of the two halves along
    // strike sit where their own segment is.
    ExtensionModelOptions o;
    o.columns = 48;
    o.layers = 15;
    o.rows = 16;
    o.settleSteps = 500;
    o.frames = 2;
    o.discontinuities = {0.5};
    o.obliquity = 0.125;
    o.segments = 2;
    ExtensionModel model(o);
    model.advance(model.frameStep(1));
    const Frame last = model.snapshot();
    const AttributeColumn* broken = last.attribute("broken_bonds");
    ASSERT_NE(broken, nullptr);
    const double ySplit = 0.5 * double(last.box.hi[1]);
    double sum[2] = {0, 0};
    std::size_t count[2] = {0, 0}, damaged = 0;
    for (std::size_t i = 0; i < last.size(); ++i) {
        if (broken->value(i) < 3)
            continue;
        ++damaged;
        const int half = last.y[i] < ySplit ? 0 : 1;
        sum[half] += last.x[i];
        ++count[half];
    }
    ASSERT_GT(count[0], 50u);
    ASSERT_GT(count[1], 50u);
    // Damage is localised: far fewer than the block's spheres.
    EXPECT_LT(double(damaged), 0.2 * double(last.size()));
    // The graben above the discontinuity follows it: its segments step 12 radii apart in x
    // (0.125 x 96), so the damaged spheres' mean x moves by about that between the halves.
    const double shift = sum[1] / double(count[1]) - sum[0] / double(count[0]);
    EXPECT_GT(shift, 6.0);
    EXPECT_LT(shift, 18.0);
}
