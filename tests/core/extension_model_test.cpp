#include "core/model/dataset.hpp"
#include "core/synth/dump_writer.hpp"
#include "core/synth/extension_model.hpp"
#include "core/synth/fault_bands.hpp"

#include "test_files.hpp"

#include <gtest/gtest.h>

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

TEST(ExtensionModel, BrokenBondsGatherInAFewNarrowDippingZones) {
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
