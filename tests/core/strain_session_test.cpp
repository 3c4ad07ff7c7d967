// strain.add / strain.remove (issue 36, JOURNAL.md "Strain from motion"): the variables act as
// columns for thresholds, histograms and CSV, undo, save and reopen with the session, and hostile
// options are refused naming the field before anything changes.
#include "core/data/frame_cache.hpp"
#include "core/data/frame_prefetcher.hpp"
#include "core/io/input_error.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "lattice_dump.hpp"
#include "session_commands.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>
#include <tuple>

using namespace faultline::core;
using faultline::test::TempDir;

namespace {

// Three frames of a 6 x 6 x 6 lattice (spacing 1, radius 0.5, ids 1..216) in which the upper
// half (z >= 3) slides east by 0.3 per frame: a horizontal fault between z = 2 and z = 3.
std::string writeSlidingBlock(const TempDir& dir) {
    std::ostringstream text;
    for (int t = 0; t < 3; ++t) {
        text << "ITEM: TIMESTEP\n"
             << t * 100 << "\nITEM: NUMBER OF ATOMS\n216\n"
             << "ITEM: BOX BOUNDS ff ff ff\n-0.5 7\n-0.5 5.5\n-0.5 5.5\n"
             << "ITEM: ATOMS id x y z radius\n";
        int id = 1;
        for (int z = 0; z < 6; ++z)
            for (int y = 0; y < 6; ++y)
                for (int x = 0; x < 6; ++x)
                    text << id++ << " " << (x + (z >= 3 ? 0.3 * t : 0.0)) << " " << y << " " << z
                         << " 0.5\n";
    }
    return dir.write("slide.dump", text.str());
}

// A frame cache in `dir` that keeps even the sliding block's small frames.
FrameCacheSettings cacheIn(const TempDir& dir, const std::string& folder) {
    FrameCacheSettings settings;
    settings.folder = dir.file(folder);
    settings.minSourceBytes = 0;
    settings.minFreeDiskBytes = 0;
    return settings;
}

using faultline::test::cmd;

void expectRefusedUnchanged(Session& s, const char* text, const std::string& message) {
    const SessionState before = s.state();
    try {
        s.apply(cmd(text));
        ADD_FAILURE() << "accepted " << text;
    } catch (const CommandError& e) {
        EXPECT_EQ(std::string(e.what()), message);
    }
    EXPECT_EQ(s.state(), before) << text;
}

// The sliding block with its incremental strains (against the frame before, face neighbours
// only), at its last frame.
void openSlidingAtFrame2(Session& s, const TempDir& dir) {
    s.apply({{"op", "data.open"}, {"paths", {writeSlidingBlock(dir)}}});
    s.apply(cmd(R"({"op":"strain.add","since_offset":-1,"cutoff":1.1,"prefix":"inc_"})"));
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
}

} // namespace

TEST(StrainSession, IncrementalShearStrainPicksOutTheSlidingPlane) {
    TempDir dir;
    Session s;
    openSlidingAtFrame2(s, dir);
    auto frame = s.currentFrame();
    for (const char* name :
         {"inc_shear_strain", "inc_volumetric_strain", "inc_d2min", "inc_displacement"})
        EXPECT_NE(frame->attribute(name), nullptr) << name;
    s.apply(cmd(R"({"op":"threshold.add","variable":"inc_shear_strain","low":0.05,"high":1e30})"));
    // Face neighbours only (cutoff 1.1): the layers z = 2 and z = 3 straddle the slip.
    EXPECT_EQ(s.visibility().visibleCount, 72u);
    // Displacement since the frame before: 0.3 above, 0 below.
    s.apply(cmd(R"({"op":"threshold.set","variable":"inc_shear_strain","enabled":false})"));
    s.apply(cmd(R"({"op":"threshold.add","variable":"inc_displacement","low":0.29,"high":0.31})"));
    EXPECT_EQ(s.visibility().visibleCount, 108u);
    // Frame 0 has no frame before it: NaN, which passes no threshold.
    s.apply(cmd(R"({"op":"frame.set","frame":0})"));
    EXPECT_EQ(s.visibility().visibleCount, 0u);
    EXPECT_TRUE(std::isnan(s.currentFrame()->attribute("inc_shear_strain")->floats[0]));

    // Cumulative strain alongside: against frame 0, without a prefix.
    s.apply(cmd(R"({"op":"strain.add","since_frame":0,"cutoff":1.1})"));
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    s.apply(cmd(R"({"op":"threshold.remove","variable":"inc_displacement"})"));
    s.apply(cmd(R"({"op":"threshold.add","variable":"displacement","low":0.59,"high":0.61})"));
    EXPECT_EQ(s.visibility().visibleCount, 108u);

    // A CSV of chosen variables, one row per sphere.
    const std::string csv = dir.file("s.csv");
    s.apply({{"op", "export.csv"},
             {"what", "spheres"},
             {"path", csv},
             {"variables", {"shear_strain", "inc_displacement"}}});
    std::ifstream in(csv);
    std::string header, row;
    std::getline(in, header);
    EXPECT_EQ(header, "id,shear_strain,inc_displacement");
    int rows = 0;
    while (std::getline(in, row))
        ++rows;
    EXPECT_EQ(rows, 216);

    // Undo takes the cumulative variables away again; the threshold on them is undone first.
    s.apply(cmd(R"({"op":"undo"})")); // threshold.add
    s.apply(cmd(R"({"op":"undo"})")); // threshold.remove
    s.apply(cmd(R"({"op":"undo"})")); // strain.add
    EXPECT_EQ(s.currentFrame()->attribute("shear_strain"), nullptr);
    EXPECT_NE(s.currentFrame()->attribute("inc_shear_strain"), nullptr);
    s.apply(cmd(R"({"op":"redo"})"));
    EXPECT_NE(s.currentFrame()->attribute("shear_strain"), nullptr);

    // Saved and reopened with the session.
    const std::string file = dir.file("a.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    Session t;
    t.apply({{"op", "session.open"}, {"path", file}});
    ASSERT_EQ(t.state().strains.size(), 2u);
    EXPECT_EQ(t.state().strains, s.state().strains);
    EXPECT_NE(t.currentFrame()->attribute("inc_d2min"), nullptr);

    s.apply(cmd(R"({"op":"strain.remove","prefix":"inc_"})"));
    EXPECT_EQ(s.currentFrame()->attribute("inc_shear_strain"), nullptr);
    EXPECT_NE(s.currentFrame()->attribute("shear_strain"), nullptr);
}

TEST(StrainSession, HostileOptionsAreRefusedNamingTheField) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeSlidingBlock(dir)}}});
    expectRefusedUnchanged(s, R"({"op":"strain.add"})",
                           "strain.add: give \"since_frame\" (a frame) or \"since_offset\" (frames "
                           "before each frame, e.g. -4)");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":0,"cutoff":0})",
                           "strain.add: \"cutoff\" must be a number > 0, found 0");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":0,"cutoff":-1.5})",
                           "strain.add: \"cutoff\" must be a number > 0, found -1.5");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":0,"cutoff":"wide"})",
                           "strain.add: \"cutoff\" must be a number > 0, found \"wide\"");
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_frame":0,"cutoff":1e300})",
        "strain.add: \"cutoff\" 1e+300 is more than 20 times the automatic one (1.5) "
        "for this data");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":3})",
                           "strain.add: \"since_frame\" 3 is out of range 0..2");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":-1})",
                           "strain.add: since_frame must be >= 0");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":1.5})",
                           "strain.add: \"since_frame\" must be a whole number, found 1.5");
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_frame":1e300})",
        "strain.add: \"since_frame\" must be a whole number of frames, found 1e+300");
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_offset":0})",
        "strain.add: since_offset must not be 0 (a frame against itself has no strain)");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_offset":-3})",
                           "strain.add: \"since_offset\" -3 reaches past all 3 frames");
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_frame":0,"since_offset":-1})",
        "strain.add: \"since_offset\" goes with no \"since_frame\": give one of them");
    expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":0,"prefix":"a b"})",
                           "strain.add: prefix may hold only letters, digits, '_', '-' and '.'");
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_frame":0,"radius":2})",
        "strain.add: unknown field \"radius\" (expected since_frame, since_offset, "
        "cutoff, prefix, index)");
    s.apply(cmd(R"({"op":"strain.add","since_frame":0})"));
    expectRefusedUnchanged(
        s, R"({"op":"strain.add","since_offset":-1})",
        "strain.add: strain variables with prefix \"\" exist already: strain.remove "
        "them first, or give another \"prefix\"");
    expectRefusedUnchanged(
        s, R"({"op":"strain.remove","prefix":"inc_"})",
        "strain.remove: no strain variables with prefix \"inc_\" (there are \"\")");
}

// Radii far larger than the centres' spacing (a radius column in millimetres beside centres in
// metres): the automatic cutoff would take in the whole model, hours of work on a large one and
// no local strain. strain.add refuses it, saying what it would take in and what to give instead;
// an explicit cutoff is taken.
TEST(StrainSession, RadiiFarLargerThanTheSpacingAskForACutoff) {
    TempDir dir;
    // Radii 20 on a spacing of 1, and a thousandth of the spacing (metres beside millimetres:
    // no sphere would have a neighbour within the automatic cutoff).
    for (const auto& [radius, automatic, around] :
         {std::tuple{"20", "60", "2743"}, std::tuple{"0.0005", "0.0015", "0"}}) {
        Session s;
        s.apply(
            {{"op", "data.open"},
             {"paths", {dir.write("r.dump", faultline::test::shearedLatticeDump(14, radius))}}});
        expectRefusedUnchanged(
            s, R"({"op":"strain.add","since_frame":0})",
            std::string("strain.add: give \"cutoff\", e.g. 1.49 (1.5 x the centres' spacing): the "
                        "automatic one, ") +
                automatic + " (1.5 x the median diameter), takes in about " + around +
                " spheres around each, where a packing's takes about 17; are the radii in "
                "another unit than the centres?");
        if (std::string(radius) == "0.0005") // 20 x 1.5 x the spacing, not x the automatic
            expectRefusedUnchanged(s, R"({"op":"strain.add","since_frame":0,"cutoff":40})",
                                   "strain.add: \"cutoff\" 40 is more than 20 times 1.5 x the "
                                   "centres' spacing (1.49) in this data");
        s.apply(cmd(R"({"op":"strain.add","since_frame":0,"cutoff":1.49})"));
        s.apply(cmd(R"({"op":"frame.set","frame":1})"));
        const AttributeColumn* shear = s.currentFrame()->attribute("shear_strain");
        ASSERT_NE(shear, nullptr);
        EXPECT_NEAR(shear->floats[1000], 0.005, 1e-4); // a simple shear of 0.01
    }
}

TEST(StrainSession, ASessionFileWithBadStrainsIsRefusedWithItsPlace) {
    TempDir dir;
    auto load = [&](const std::string& strains) {
        const std::string path =
            dir.write("bad.faultline.json",
                      R"({"format":"faultline-session","schema":1,"strains":)" + strains + "}");
        try {
            loadSessionFile(path);
        } catch (const InputError& e) {
            return std::string(e.what()).substr(path.size());
        }
        return std::string("loaded");
    };
    EXPECT_EQ(load(R"([{"since_offset":0}])"),
              ": strains[0].since_offset: must not be 0 (a frame against itself has no strain)");
    EXPECT_EQ(load(R"([{"cutoff":1}])"), ": strains[0]: needs \"since_frame\" or \"since_offset\"");
    EXPECT_EQ(load(R"([{"since_frame":0},{"since_frame":1}])"),
              ": strains[1].prefix: '' is used twice");
    EXPECT_EQ(load(R"([{"since_frame":0,"cutoff":-2}])"),
              ": strains[0].cutoff: must be a number > 0");
    EXPECT_EQ(load(R"([{"since_frame":0,"prefix":"inc_"}])"), "loaded");
}

// Derived frames go to the binary frame cache beside the frames read: a second dataset on the
// same files gets them without deriving, and a changed spec or source is a miss.
TEST(StrainSession, DerivedFramesAreKeptInTheFrameCache) {
    TempDir dir;
    const std::string dump = writeSlidingBlock(dir);
    auto cache = std::make_shared<FrameCache>(cacheIn(dir, "cache"));
    const std::vector<StrainSpec> strains = {StrainSpec{true, -1, 1.1, "inc_"}};
    auto first = Dataset::open({dump});
    first->setFrameCache(cache);
    first->setStrains(strains);
    const auto derived = first->frame(2);
    ASSERT_NE(derived->attribute("inc_shear_strain"), nullptr);
    const auto writes = cache->stats().writes;
    EXPECT_GE(writes, 2u); // frame 2 as read (its reference, frame 1, too) and as derived

    auto second = Dataset::open({dump});
    second->setFrameCache(cache);
    second->setStrains(strains);
    const auto hits = cache->stats().hits;
    const auto again = second->frame(2);
    EXPECT_EQ(cache->stats().hits, hits + 1);
    EXPECT_EQ(cache->stats().writes, writes);
    ASSERT_NE(again->attribute("inc_shear_strain"), nullptr);
    EXPECT_EQ(again->attribute("inc_shear_strain")->floats,
              derived->attribute("inc_shear_strain")->floats);
    EXPECT_EQ(again->derivedColumns, 7u);
    // Taking the spec away gives the frame as read.
    second->setStrains({});
    EXPECT_EQ(second->frame(2)->attribute("inc_shear_strain"), nullptr);
    EXPECT_EQ(second->frame(2)->derivedColumns, 0u);
    // Another cutoff is another derived frame.
    second->setStrains({StrainSpec{true, -1, 1.6, "inc_"}});
    const auto other = second->frame(2);
    EXPECT_GT(cache->stats().writes, writes);
    EXPECT_NE(other->attribute("inc_shear_strain")->floats,
              derived->attribute("inc_shear_strain")->floats);
}

// A frame derived now is out (in memory, the caller told) before it is written to the frame
// cache, which the view need not wait for; the write still happens, on the same thread.
TEST(StrainSession, ADerivedFrameIsReadyBeforeItIsWrittenToTheFrameCache) {
    TempDir dir;
    const std::string dump = writeSlidingBlock(dir);
    auto cache = std::make_shared<FrameCache>(cacheIn(dir, "cache"));
    auto ds = Dataset::open({dump});
    ds->setFrameCache(cache);
    ds->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    bool inMemory = false, called = false;
    std::uint64_t writesWhenReady = 0;
    const auto f = ds->frame(1, [&] {
        called = true;
        inMemory = ds->isCached(1);
        writesWhenReady = cache->stats().writes;
    });
    EXPECT_TRUE(called);
    EXPECT_TRUE(inMemory);
    EXPECT_EQ(cache->stats().writes, writesWhenReady + 1); // the derived frame, after
    auto again = Dataset::open({dump});
    again->setFrameCache(cache);
    again->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    const auto hits = cache->stats().hits;
    EXPECT_EQ(again->frame(1)->attribute("inc_shear_strain")->floats,
              f->attribute("inc_shear_strain")->floats);
    EXPECT_EQ(cache->stats().hits, hits + 1);
    // The background pass finds it stored from its file's header; a corrupt header is dropped
    // (and the frame stored again), a corrupt column is left to the read that meets it.
    Dataset::BaseFrames bases;
    const auto writesBefore = cache->stats().writes;
    EXPECT_TRUE(ds->storeDerivedFrame(1, bases));
    EXPECT_EQ(cache->stats().writes, writesBefore);
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir.file("cache")))
        files.push_back(e.path().string());
    for (const auto& file : files) // headers cut short: every file (plain or derived) corrupt
        std::filesystem::resize_file(file, 100);
    const auto rejected = cache->stats().rejected;
    EXPECT_TRUE(ds->storeDerivedFrame(1, bases));
    EXPECT_GT(cache->stats().rejected, rejected);
    EXPECT_EQ(cache->stats().writes, writesBefore + 1);

    // A frame in memory already: ready at once, nothing written.
    called = false;
    const auto writes = cache->stats().writes;
    EXPECT_EQ(ds->frame(1, [&] { called = true; }), f);
    EXPECT_TRUE(called);
    EXPECT_EQ(cache->stats().writes, writes);
}

// The workbench's background pass (FramePrefetcher::setBackgroundDerivation): every frame's
// strain goes to the frame cache while the views are idle, without being held in memory, so a
// later scrub reads derived frames; new strains start the pass again; a run too large for half
// the cache's budget is left alone.
TEST(StrainSession, ABackgroundPassDerivesEveryFrameIntoTheFrameCache) {
    TempDir dir;
    const std::string dump = writeSlidingBlock(dir);
    const FrameCacheSettings settings = cacheIn(dir, "cache");
    auto cache = std::make_shared<FrameCache>(settings);
    auto ds = Dataset::open({dump});
    ds->setFrameCache(cache);
    ds->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    PrefetchSettings viewOnly; // no frames read ahead for the view: what is in memory is its own
    viewOnly.lookAhead = 0;
    FramePrefetcher prefetcher(ds, viewOnly);
    EXPECT_FALSE(prefetcher.backgroundProgress().running); // off until asked for
    prefetcher.setBackgroundDerivation(true);
    auto passDone = [&] {
        for (int k = 0; k < 3000; ++k) {
            const auto p = prefetcher.backgroundProgress();
            if (p.total > 0 && p.done == p.total && !p.running)
                return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    };
    // A frame for the view, within a generous time (a failed load fails the test, not hangs it).
    auto show = [](FramePrefetcher& p, std::size_t frame = 0) {
        for (int k = 0; k < 15000; ++k) {
            if (p.request(frame).status == FrameStatus::Ready)
                return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        return false;
    };
    // The pass waits for a frame in memory (the size of a frame tells whether the run fits).
    ASSERT_TRUE(show(prefetcher));
    ASSERT_TRUE(passDone());
    EXPECT_EQ(prefetcher.backgroundProgress().total, 3u);
    EXPECT_FALSE(ds->isCached(1));
    EXPECT_FALSE(ds->isCached(2));

    // Another dataset on the same files reads every derived frame from the cache, as derived.
    auto again = Dataset::open({dump});
    again->setFrameCache(cache);
    again->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    const auto writes = cache->stats().writes;
    const auto hits = cache->stats().hits;
    for (std::size_t k = 0; k < 3; ++k) {
        const auto f = again->frame(k);
        ASSERT_NE(f->attribute("inc_shear_strain"), nullptr);
        EXPECT_EQ(f->derivedColumns, 7u);
    }
    EXPECT_EQ(cache->stats().hits, hits + 3);
    EXPECT_EQ(cache->stats().writes, writes);
    auto direct = Dataset::open({dump});
    direct->setFrameCache(nullptr);
    direct->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    EXPECT_EQ(again->frame(2)->attribute("inc_shear_strain")->floats,
              direct->frame(2)->attribute("inc_shear_strain")->floats);

    // New strains: the pass starts again and stores each frame derived the new way.
    ds->setStrains({StrainSpec{false, 0, 1.6, ""}});
    ASSERT_TRUE(show(prefetcher));
    ASSERT_TRUE(passDone());
    EXPECT_GE(cache->stats().writes, writes + 2); // frames 1 and 2 (frame 0 derived for the view)

    // Turned off and on again (within a frame or between two), and started from the frame the
    // view shows (1, then 2, then around to 0): every frame is still readied.
    ds->setStrains({StrainSpec{true, -1, 1.4, "inc_"}});
    ASSERT_TRUE(show(prefetcher, 1));
    prefetcher.setBackgroundDerivation(false);
    prefetcher.setBackgroundDerivation(true);
    ASSERT_TRUE(passDone());
    EXPECT_EQ(prefetcher.backgroundProgress().done, 3u);
    auto third = Dataset::open({dump});
    third->setFrameCache(cache);
    third->setStrains({StrainSpec{true, -1, 1.4, "inc_"}});
    const auto hitsBefore = cache->stats().hits;
    for (std::size_t k = 0; k < 3; ++k)
        third->frame(k);
    EXPECT_EQ(cache->stats().hits, hitsBefore + 3);

    // The same sources with a frame cache of `s`, the pass on and frame 0 shown.
    auto passWith = [&](const FrameCacheSettings& s) {
        auto run = Dataset::open({dump});
        run->setFrameCache(std::make_shared<FrameCache>(s));
        run->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
        auto pass = std::make_unique<FramePrefetcher>(run);
        pass->setBackgroundDerivation(true);
        EXPECT_TRUE(show(*pass));
        return pass;
    };
    // A run over half the cache's budget: no pass.
    FrameCacheSettings small = settings;
    small.folder = dir.file("small");
    small.budgetBytes = 1000;
    const auto idle = passWith(small);
    idle->waitIdle(std::chrono::seconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(idle->backgroundProgress().running);
    EXPECT_EQ(idle->backgroundProgress().done, 0u);
    // ... and the Data panel says why.
    using Held = FramePrefetcher::BackgroundProgress::Held;
    EXPECT_EQ(idle->backgroundProgress().held, Held::RunTooLarge);
    EXPECT_GT(idle->backgroundProgress().runBytes, idle->backgroundProgress().budgetBytes);
    EXPECT_EQ(idle->backgroundProgress().budgetBytes, 500u);
    EXPECT_EQ(prefetcher.backgroundProgress().held, Held::None); // done

    // The frame cache off, or refusing files (a disk short of room): no pass, and why.
    for (const bool off : {true, false}) {
        FrameCacheSettings s = settings;
        s.folder = dir.file(off ? "off" : "short");
        s.enabled = !off;
        s.minFreeDiskBytes = off ? 0 : std::uint64_t(1) << 62;
        const auto held = passWith(s);
        for (int k = 0; k < 2000 && held->backgroundProgress().held == Held::None; ++k)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        const auto p = held->backgroundProgress();
        EXPECT_EQ(p.held, off ? Held::CacheOff : Held::CacheRefusesWrites) << off;
        EXPECT_FALSE(p.running);
        EXPECT_LT(p.done, p.total);
    }

    // Sources the cache does not keep (smaller than its minSourceBytes): nothing to store.
    FrameCacheSettings large = settings;
    large.folder = dir.file("large");
    large.minSourceBytes = 1 << 20;
    auto smallRun = Dataset::open({dump});
    smallRun->setFrameCache(std::make_shared<FrameCache>(large));
    smallRun->setStrains({StrainSpec{true, -1, 1.1, "inc_"}});
    EXPECT_FALSE(smallRun->storesDerived());
    Dataset::BaseFrames bases;
    EXPECT_FALSE(smallRun->storeDerivedFrame(2, bases));
    EXPECT_TRUE(ds->storesDerived());

    // A pass keeps only the frames read that frames ahead take as references: against the
    // frame two before, frame 0 until frame 2 is done; frame 1 is no frame's (there is no 3).
    auto pass = Dataset::open({dump});
    pass->setFrameCache(std::make_shared<FrameCache>(cacheIn(dir, "fresh")));
    pass->setStrains({StrainSpec{true, -2, 1.1, "inc2_"}});
    Dataset::BaseFrames kept;
    auto keys = [&] {
        std::vector<std::size_t> k;
        for (const auto& [index, frame] : kept)
            k.push_back(index);
        return k;
    };
    EXPECT_TRUE(pass->storeDerivedFrame(0, kept));
    EXPECT_EQ(keys(), std::vector<std::size_t>{0});
    EXPECT_TRUE(pass->storeDerivedFrame(1, kept));
    EXPECT_EQ(keys(), std::vector<std::size_t>{0});
    EXPECT_TRUE(pass->storeDerivedFrame(2, kept));
    EXPECT_TRUE(keys().empty());
    EXPECT_EQ(pass->cachedFrameCount(), 0u);       // nothing in memory's cache
    EXPECT_TRUE(pass->storeDerivedFrame(2, kept)); // found stored
    // Cancelled: nothing stored.
    pass->setStrains({StrainSpec{true, -1, 1.3, "inc3_"}});
    const std::atomic<bool> cancel{true};
    EXPECT_FALSE(pass->storeDerivedFrame(1, kept, &cancel));
}

// An export after surface.build (or a second export, or a new iso-value within the built range)
// takes the surface the session built in this frame, and never one built on other values: a
// frame change empties the session's surfaces first, and strains derived again in the same frame
// key the surfaces coloured by them anew (Frame::derivation).
TEST(StrainSession, ExportsReuseTheBuiltSurfaceAndNeverAStaleOne) {
    TempDir dir;
    Session s;
    openSlidingAtFrame2(s, dir);
    s.apply(cmd(R"({"op":"threshold.add","variable":"inc_shear_strain","low":0.05,"high":1e30})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","kernel":"inverse-square","voxel":0.25,)"
                R"("iso":1.5,"color_by":"inc_shear_strain","map":"gray","range":[0,0.5]})"));
    const SurfaceCache& cache = s.surfaceCache();
    EXPECT_EQ(cache.counters().builds, 1u);
    s.apply({{"op", "export.vdb"}, {"fault", "F1"}, {"path", dir.file("F1.vdb")}});
    s.apply({{"op", "export.gltf"}, {"faults", {"F1"}}, {"path", dir.file("F1.glb")}});
    EXPECT_EQ(cache.counters().builds, 1u);
    EXPECT_EQ(cache.counters().hits, 2u);
    // The same mesh as a build of its own.
    const FaultSurfaceRequest request = surfaceRequestFor(s, "F1", "test");
    const SurfaceResult own = buildFaultSurface(*s.currentFrame(), request);
    const SurfaceResult kept =
        cache.find(surfaceKeyOf(2, s.currentFrame().get(), request.fault, request.settings,
                                surfaceParamsOf(request.settings, request.fault)),
                   1.5f);
    ASSERT_NE(kept.field, nullptr);
    EXPECT_EQ(kept.mesh.positions, own.mesh.positions);
    EXPECT_EQ(kept.mesh.colors, own.mesh.colors);
    EXPECT_EQ(kept.mesh.indices, own.mesh.indices);
    // Another iso-value inside the built range (iso x or / 1.05): re-meshed from the kept field.
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","iso":1.55})"));
    EXPECT_EQ(cache.counters().builds, 1u);
    EXPECT_EQ(cache.counters().remeshes, 1u);

    // Another frame: built there, and again on coming back (the cache holds one frame).
    s.apply(cmd(R"({"op":"frame.set","frame":1})"));
    s.apply({{"op", "export.vdb"}, {"fault", "F1"}, {"path", dir.file("F1-1.vdb")}});
    EXPECT_EQ(cache.counters().builds, 2u);
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    // Strains derived again (a second set of variables) make new frames: the colours' values
    // may have changed, so the surface is built again, not taken from before.
    s.apply(cmd(R"({"op":"strain.add","since_frame":0,"cutoff":1.1})"));
    s.apply({{"op", "export.gltf"}, {"faults", {"F1"}}, {"path", dir.file("F1-2.glb")}});
    EXPECT_EQ(cache.counters().builds, 3u);
    EXPECT_EQ(cache.counters().hits, 2u);
    // In the same frame, with no frame change between: the second set derived again with
    // another cutoff gives its variables other values, and a surface coloured by one of them is
    // built again; a second export then takes it.
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","color_by":"shear_strain"})"));
    s.apply({{"op", "export.gltf"}, {"faults", {"F1"}}, {"path", dir.file("F1-3.glb")}});
    EXPECT_EQ(cache.counters().builds, 4u);
    s.apply(cmd(R"({"op":"strain.remove","prefix":""})"));
    s.apply(cmd(R"({"op":"strain.add","since_frame":0,"cutoff":1.6})"));
    s.apply({{"op", "export.gltf"}, {"faults", {"F1"}}, {"path", dir.file("F1-4.glb")}});
    EXPECT_EQ(cache.counters().builds, 5u);
    s.apply({{"op", "export.gltf"}, {"faults", {"F1"}}, {"path", dir.file("F1-5.glb")}});
    EXPECT_EQ(cache.counters().builds, 5u);
    EXPECT_EQ(cache.counters().hits, 3u);
}

// A surface coloured by a derived variable keys by the strain list that derived the frame, so a
// cache that outlives frame objects (the workbench's) never gives the colours of other values:
// the same names derived again with another cutoff or reference make another key. Colours by a
// variable read from the file, or by none, keep theirs.
TEST(StrainSession, ASurfaceColouredByDerivedValuesKeysByTheirDerivation) {
    TempDir dir;
    Session s;
    openSlidingAtFrame2(s, dir);
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2,3,4,5,6,7,8]})"));
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","color_by":"inc_shear_strain"})"));
    auto keyOf = [&](const std::string& colorBy) {
        SurfaceSettings settings = *s.state().surface("F1");
        settings.colorBy = colorBy;
        const Fault& fault = *s.state().fault("F1");
        return surfaceKeyOf(2, s.currentFrame().get(), fault, settings,
                            surfaceParamsOf(settings, fault));
    };
    const auto first = s.currentFrame();
    ASSERT_NE(first->derivation, 0u);
    const SurfaceKey derived = keyOf("inc_shear_strain");
    const SurfaceKey read = keyOf("strain");
    const SurfaceKey plain = keyOf("");
    // The same list again (another frame object, e.g. reloaded): the same keys.
    s.apply(cmd(R"({"op":"frame.set","frame":1})"));
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    EXPECT_EQ(s.currentFrame()->derivation, first->derivation);
    EXPECT_EQ(keyOf("inc_shear_strain"), derived);
    // Derived again under the same prefix with another cutoff: other values, another key.
    s.apply(cmd(R"({"op":"strain.remove","prefix":"inc_"})"));
    s.apply(cmd(R"({"op":"strain.add","since_offset":-1,"cutoff":1.6,"prefix":"inc_"})"));
    ASSERT_NE(s.currentFrame()->attribute("inc_shear_strain")->floats,
              first->attribute("inc_shear_strain")->floats);
    EXPECT_NE(s.currentFrame()->derivation, first->derivation);
    EXPECT_NE(keyOf("inc_shear_strain"), derived);
    EXPECT_EQ(keyOf("strain"), read);
    EXPECT_EQ(keyOf(""), plain);
}
