#include "core/data/dataset.hpp"
#include "core/data/frame_cache.hpp"
#include "core/data/frame_cache_format.hpp"
#include "core/io/frame_source.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

using namespace faultline::core;
using faultline::test::TempDir;
namespace fs = std::filesystem;

namespace {

// A frame exercising every field: sparse and negative ids, odd floats, both column types.
Frame everyFieldFrame() {
    Frame f;
    f.timestep = -1234567890123LL;
    f.ids = {7, -3, 1000000000000LL, 42};
    f.x = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(), 1e30f};
    f.y = {1.5f, std::numeric_limits<float>::quiet_NaN(), -2.25f, 3.0f};
    f.z = {std::numeric_limits<float>::max(), 0.1f, 0.2f, -0.3f};
    f.radius = {0.5f, 0.25f, 0.125f, 1.0f};
    f.radiusIsDefault = true;
    f.idsAreRowNumbers = true;
    f.box.lo = {-1.5, -2.5, -3.5};
    f.box.hi = {10.125, 20.0625, 30.5};
    f.box.triclinic = true;
    f.box.xy = 0.5;
    f.box.xz = -0.25;
    f.box.yz = 1e-9;
    f.box.periodic = {true, false, true};
    f.box.known = true;
    AttributeColumn strain;
    strain.name = "c_strain[2]";
    strain.floats = {0.1f, -0.2f, std::numeric_limits<float>::infinity(), 0.4f};
    AttributeColumn bonds;
    bonds.name = "broken_bonds";
    bonds.type = ColumnType::Int32;
    bonds.ints = {0, std::numeric_limits<std::int32_t>::min(), 12,
                  std::numeric_limits<std::int32_t>::max()};
    AttributeColumn unnamed; // an empty name is legal in a CSV header
    unnamed.type = ColumnType::Int32;
    unnamed.ints = {1, 2, 3, 4};
    f.attributes = {strain, bonds, unnamed};
    f.finalize();
    return f;
}

template <typename T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectIdentical(const Frame& a, const Frame& b) {
    EXPECT_EQ(a.timestep, b.timestep);
    EXPECT_TRUE(sameBits(a.ids, b.ids));
    EXPECT_TRUE(sameBits(a.x, b.x));
    EXPECT_TRUE(sameBits(a.y, b.y));
    EXPECT_TRUE(sameBits(a.z, b.z));
    EXPECT_TRUE(sameBits(a.radius, b.radius));
    EXPECT_EQ(a.radiusIsDefault, b.radiusIsDefault);
    EXPECT_EQ(a.idsAreRowNumbers, b.idsAreRowNumbers);
    EXPECT_EQ(a.box.lo, b.box.lo);
    EXPECT_EQ(a.box.hi, b.box.hi);
    EXPECT_EQ(a.box.triclinic, b.box.triclinic);
    EXPECT_EQ(a.box.xy, b.box.xy);
    EXPECT_EQ(a.box.xz, b.box.xz);
    EXPECT_EQ(a.box.yz, b.box.yz);
    EXPECT_EQ(a.box.periodic, b.box.periodic);
    EXPECT_EQ(a.box.known, b.box.known);
    ASSERT_EQ(a.attributes.size(), b.attributes.size());
    for (std::size_t k = 0; k < a.attributes.size(); ++k) {
        const auto &ca = a.attributes[k], &cb = b.attributes[k];
        EXPECT_EQ(ca.name, cb.name);
        EXPECT_EQ(ca.type, cb.type);
        EXPECT_TRUE(sameBits(ca.floats, cb.floats)) << ca.name;
        EXPECT_TRUE(sameBits(ca.ints, cb.ints)) << ca.name;
        EXPECT_EQ(ca.min, cb.min) << ca.name;
        EXPECT_EQ(ca.max, cb.max) << ca.name;
    }
    EXPECT_EQ(a.centreMin(), b.centreMin());
    EXPECT_EQ(a.centreMax(), b.centreMax());
    for (std::int64_t id : a.ids)
        EXPECT_EQ(a.rowOf(id), b.rowOf(id));
}

std::string dumpFrame(long timestep, int atoms, float shift) {
    std::string s = "ITEM: TIMESTEP\n" + std::to_string(timestep) + "\nITEM: NUMBER OF ATOMS\n" +
                    std::to_string(atoms) +
                    "\nITEM: BOX BOUNDS pp pp ff\n0 10\n0 20\n0 30\nITEM: ATOMS id x y z radius "
                    "strain broken_bonds\n";
    for (int i = 0; i < atoms; ++i)
        s += std::to_string(i + 1) + " " + std::to_string(i * 0.5f + shift) + " 1.25 2.5 0.5 " +
             std::to_string(0.01f * i) + " " + std::to_string(i % 5) + "\n";
    return s;
}

FrameCacheSettings settingsIn(const TempDir& dir) {
    FrameCacheSettings s;
    s.folder = dir.file("cache");
    s.minSourceBytes = 0;
    s.minFreeDiskBytes = 0;
    return s;
}

FrameLocation onlyFrame(const std::string& path) {
    auto frames = indexDataFile(path);
    EXPECT_EQ(frames.size(), 1u);
    return frames.front();
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}
void writeAll(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

} // namespace

TEST(FrameCacheFormat, RoundTripKeepsEveryBit) {
    TempDir dir;
    const Frame f = everyFieldFrame();
    const std::string path = dir.file("f.flframe");
    const std::uint64_t bytes = writeCachedFrame(path, "key-1", f);
    EXPECT_EQ(bytes, fs::file_size(path));
    EXPECT_EQ(bytes % 4, 0u);
    CachedFrameRead r = readCachedFrame(path, "key-1");
    ASSERT_EQ(r.status, CachedFrameStatus::Ok) << r.detail;
    expectIdentical(f, *r.frame);
    EXPECT_EQ(r.frame->rowOf(1000000000000LL), 2u);
    EXPECT_EQ(readCachedFrame(path, "key-2").status, CachedFrameStatus::Stale);
    EXPECT_EQ(readCachedFrame(dir.file("none"), "key-1").status, CachedFrameStatus::Missing);
}

TEST(FrameCacheFormat, EmptyFrameRoundTrips) {
    TempDir dir;
    Frame f;
    f.finalize();
    writeCachedFrame(dir.file("e"), "k", f);
    CachedFrameRead r = readCachedFrame(dir.file("e"), "k");
    ASSERT_EQ(r.status, CachedFrameStatus::Ok) << r.detail;
    EXPECT_EQ(r.frame->size(), 0u);
}

TEST(FrameCacheFormat, CorruptFilesAreRejectedNeverTrusted) {
    TempDir dir;
    const std::string path = dir.file("f.flframe");
    writeCachedFrame(path, "k", everyFieldFrame());
    const std::string good = readAll(path);
    auto statusOf = [&](const std::string& bytes) {
        writeAll(path, bytes);
        return readCachedFrame(path, "k").status;
    };
    EXPECT_EQ(statusOf(""), CachedFrameStatus::Corrupt);
    EXPECT_EQ(statusOf(good.substr(0, 100)), CachedFrameStatus::Corrupt);             // header cut
    EXPECT_EQ(statusOf(good.substr(0, good.size() - 1)), CachedFrameStatus::Corrupt); // data cut
    EXPECT_EQ(statusOf(good + "tail"), CachedFrameStatus::Corrupt);                   // size lies
    std::string magic = good;
    magic[0] = 'X';
    EXPECT_EQ(statusOf(magic), CachedFrameStatus::Corrupt);
    std::string flipped = good;
    flipped[flipped.size() - 3] ^= 0x10; // a value in the last column
    EXPECT_EQ(statusOf(flipped), CachedFrameStatus::Corrupt);
    std::string header = good;
    header[24] ^= 0x01; // particle count, header checksum not updated
    EXPECT_EQ(statusOf(header), CachedFrameStatus::Corrupt);
    EXPECT_EQ(statusOf(std::string(4096, '\xff')), CachedFrameStatus::Corrupt);

    // A hostile file: a particle count of 2^40 with a correct header checksum. Sizes are checked
    // against the file before anything is allocated. (Header layout: count at byte 24, header
    // checksum at 136 over the 136 bytes before it.)
    std::string hostile = good;
    const std::uint64_t huge = 1ull << 40;
    std::memcpy(hostile.data() + 24, &huge, 8);
    const std::uint64_t sum = detail::checksum64(hostile.data(), 136, 0x4845414445520001ULL);
    std::memcpy(hostile.data() + 136, &sum, 8);
    writeAll(path, hostile);
    CachedFrameRead r = readCachedFrame(path, "k");
    EXPECT_EQ(r.status, CachedFrameStatus::Corrupt);
    EXPECT_NE(r.detail.find("particle count"), std::string::npos) << r.detail;

    // Columns that all point at the same bytes (an allocation bomb: each would be read in
    // full), with both checksums correct. Layout: key at 144, then 32-byte column entries
    // {kind, nameBytes, offset, bytes, checksum}; meta checksum at 128.
    std::string overlapping = good;
    const std::size_t table = 144 + 1; // key "k"
    std::uint64_t idsOffset;
    std::memcpy(&idsOffset, overlapping.data() + table + 8, 8);
    std::memcpy(overlapping.data() + table + 32 + 8, &idsOffset, 8); // x starts where ids do
    std::uint32_t keyBytes, columns, namesBytes;
    std::memcpy(&columns, overlapping.data() + 40, 4);
    std::memcpy(&keyBytes, overlapping.data() + 48, 4);
    std::memcpy(&namesBytes, overlapping.data() + 52, 4);
    const std::uint64_t meta = detail::checksum64(
        overlapping.data() + 144, keyBytes + columns * 32u + namesBytes, 0x4d455441ULL);
    std::memcpy(overlapping.data() + 128, &meta, 8);
    const std::uint64_t head = detail::checksum64(overlapping.data(), 136, 0x4845414445520001ULL);
    std::memcpy(overlapping.data() + 136, &head, 8);
    writeAll(path, overlapping);
    r = readCachedFrame(path, "k");
    EXPECT_EQ(r.status, CachedFrameStatus::Corrupt);
    EXPECT_NE(r.detail.find("overlaps"), std::string::npos) << r.detail;
}

// A peek (the background strain pass asking whether a frame is stored) checks the header, the
// metadata's checksum and the key as a read does, not the column table or the columns.
TEST(FrameCacheFormat, APeekChecksTheHeaderAndKeyButNotTheColumns) {
    TempDir dir;
    const std::string path = dir.file("f.flframe");
    writeCachedFrame(path, "k", everyFieldFrame());
    const std::string good = readAll(path);
    EXPECT_EQ(peekCachedFrame(path, "k"), CachedFrameStatus::Ok);
    EXPECT_EQ(peekCachedFrame(path, "other"), CachedFrameStatus::Stale);
    EXPECT_EQ(peekCachedFrame(dir.file("none"), "k"), CachedFrameStatus::Missing);
    std::string detail;
    writeAll(path, good.substr(0, 100));
    EXPECT_EQ(peekCachedFrame(path, "k", &detail), CachedFrameStatus::Corrupt);
    EXPECT_NE(detail.find("header"), std::string::npos) << detail;
    writeAll(path, good.substr(0, good.size() - 1)); // the size the header gives is checked
    EXPECT_EQ(peekCachedFrame(path, "k"), CachedFrameStatus::Corrupt);
    std::string flipped = good;
    flipped[flipped.size() - 3] ^= 0x10; // a value in the last column: only a read sees it
    writeAll(path, flipped);
    EXPECT_EQ(peekCachedFrame(path, "k"), CachedFrameStatus::Ok);
    EXPECT_EQ(readCachedFrame(path, "k").status, CachedFrameStatus::Corrupt);
    for (std::size_t length = 0; length < good.size(); length += 7) {
        writeAll(path, good.substr(0, length));
        ASSERT_EQ(peekCachedFrame(path, "k"), CachedFrameStatus::Corrupt) << length;
    }
}

TEST(FrameCacheFormat, EveryTruncationAndByteFlipIsCaught) {
    TempDir dir;
    const std::string path = dir.file("f.flframe");
    const Frame truth = everyFieldFrame();
    writeCachedFrame(path, "k", truth);
    const std::string good = readAll(path);
    for (std::size_t length = 0; length < good.size(); ++length) {
        writeAll(path, good.substr(0, length));
        ASSERT_EQ(readCachedFrame(path, "k").status, CachedFrameStatus::Corrupt) << length;
    }
    // A flipped bit anywhere: rejected, or (in alignment padding) the frame exactly as it was.
    for (std::size_t at = 0; at < good.size(); ++at) {
        std::string bad = good;
        bad[at] ^= static_cast<char>(1u << (at % 8));
        writeAll(path, bad);
        CachedFrameRead r = readCachedFrame(path, "k");
        if (r.status == CachedFrameStatus::Ok)
            expectIdentical(truth, *r.frame);
        else
            ASSERT_EQ(r.status, CachedFrameStatus::Corrupt) << at;
    }
}

TEST(FrameCache, SecondLoadComesFromTheCacheAndEqualsTheParse) {
    TempDir dir;
    const std::string src = dir.write("one.dump", dumpFrame(100, 50, 0.0f));
    FrameCache cache(settingsIn(dir));
    const FrameLocation loc = onlyFrame(src);
    const Frame parsed = loadFrame(loc);
    const Frame first = cache.fetch(loc);
    EXPECT_EQ(cache.stats().misses, 1u);
    EXPECT_EQ(cache.stats().writes, 1u);
    ASSERT_TRUE(fs::exists(cache.pathFor(loc)));
    const Frame second = cache.fetch(loc);
    EXPECT_EQ(cache.stats().hits, 1u);
    expectIdentical(parsed, first);
    expectIdentical(parsed, second);
    EXPECT_EQ(cache.problem(), "");
}

TEST(FrameCache, ChangedSourceInvalidates) {
    TempDir dir;
    const std::string src = dir.write("one.dump", dumpFrame(100, 20, 0.0f));
    FrameCache cache(settingsIn(dir));
    cache.fetch(onlyFrame(src));

    // Touch: same bytes, newer mtime. The cached frame is not used, and is rewritten.
    fs::last_write_time(src, fs::last_write_time(src) + std::chrono::seconds(5));
    cache.fetch(onlyFrame(src));
    EXPECT_EQ(cache.stats().hits, 0u);
    EXPECT_EQ(cache.stats().writes, 2u);
    cache.fetch(onlyFrame(src));
    EXPECT_EQ(cache.stats().hits, 1u);

    // New content of another size: the new values, never the cached ones.
    writeAll(src, dumpFrame(200, 30, 7.0f));
    const Frame f = cache.fetch(onlyFrame(src));
    EXPECT_EQ(f.timestep, 200);
    EXPECT_EQ(f.size(), 30u);
    EXPECT_FLOAT_EQ(f.x[0], 7.0f);
    EXPECT_EQ(cache.stats().hits, 1u);
    expectIdentical(loadFrame(onlyFrame(src)), cache.fetch(onlyFrame(src)));
    EXPECT_EQ(cache.stats().hits, 2u);
}

TEST(FrameCache, FramesOfOneFileAreCachedApart) {
    TempDir dir;
    const std::string src = dir.write(
        "multi.dump", dumpFrame(0, 10, 0.0f) + dumpFrame(10, 10, 1.0f) + dumpFrame(20, 12, 2.0f));
    FrameCache cache(settingsIn(dir));
    const auto frames = indexDataFile(src);
    ASSERT_EQ(frames.size(), 3u);
    for (const auto& loc : frames)
        cache.fetch(loc);
    for (const auto& loc : frames)
        expectIdentical(loadFrame(loc), cache.fetch(loc));
    EXPECT_EQ(cache.stats().hits, 3u);
    EXPECT_NE(cache.pathFor(frames[0]), cache.pathFor(frames[1]));
}

TEST(FrameCache, CorruptCacheFileIsIgnoredAndRebuilt) {
    TempDir dir;
    const std::string src = dir.write("one.dump", dumpFrame(100, 40, 0.5f));
    FrameCache cache(settingsIn(dir));
    const FrameLocation loc = onlyFrame(src);
    const Frame truth = loadFrame(loc);
    cache.fetch(loc);
    const std::string cached = cache.pathFor(loc);
    const std::string good = readAll(cached);

    const std::string damaged[] = {good.substr(0, good.size() / 2), "FLTFRAM\x1a garbage",
                                   good + std::string(64, '\0')};
    std::uint64_t rejected = 0;
    for (const auto& bytes : damaged) {
        writeAll(cached, bytes);
        expectIdentical(truth, cache.fetch(loc)); // parsed again from the source
        EXPECT_EQ(cache.stats().rejected, ++rejected);
        EXPECT_EQ(readAll(cached), good); // and written afresh
    }
    EXPECT_NE(cache.problem().find("corrupt"), std::string::npos) << cache.problem();
    const auto hits = cache.stats().hits;
    cache.fetch(loc);
    EXPECT_EQ(cache.stats().hits, hits + 1);
}

TEST(FrameCache, UnwritableFolderFallsBackToParsing) {
    TempDir dir;
    const std::string src = dir.write("one.dump", dumpFrame(100, 10, 0.0f));
    dir.write("plain-file", "not a folder");
    FrameCacheSettings s = settingsIn(dir);
    s.folder = dir.file("plain-file/cache"); // fails even for root: a file is in the way
    FrameCache cache(s);
    const FrameLocation loc = onlyFrame(src);
    expectIdentical(loadFrame(loc), cache.fetch(loc));
    expectIdentical(loadFrame(loc), cache.fetch(loc));
    EXPECT_FALSE(cache.problem().empty());
    EXPECT_EQ(cache.stats().writes, 0u);
    EXPECT_EQ(cache.stats().hits, 0u);
}

TEST(FrameCache, DisabledOrSmallSourcesWriteNothing) {
    TempDir dir;
    const std::string src = dir.write("one.dump", dumpFrame(100, 10, 0.0f));
    FrameCacheSettings off = settingsIn(dir);
    off.enabled = false;
    FrameCache disabled(off);
    disabled.fetch(onlyFrame(src));
    EXPECT_FALSE(fs::exists(dir.file("cache")));
    FrameCacheSettings small = settingsIn(dir);
    small.minSourceBytes = fs::file_size(src) + 1;
    FrameCache tooSmall(small);
    tooSmall.fetch(onlyFrame(src));
    EXPECT_FALSE(fs::exists(dir.file("cache")));
}

TEST(FrameCache, FolderBudgetEvictsTheOldest) {
    TempDir dir;
    std::string text;
    for (int t = 0; t < 4; ++t)
        text += dumpFrame(t, 200, float(t));
    const std::string src = dir.write("multi.dump", text);
    const auto frames = indexDataFile(src);
    FrameCacheSettings s = settingsIn(dir);
    FrameCache probe(s);
    probe.fetch(frames[0]);
    const std::uint64_t oneFile = fs::file_size(probe.pathFor(frames[0]));
    probe.clear();
    EXPECT_FALSE(fs::exists(probe.pathFor(frames[0])));

    s.budgetBytes = oneFile * 2 + oneFile / 2; // room for two files
    FrameCache cache(s);
    for (const auto& loc : frames) {
        cache.fetch(loc);
        // distinct mtimes, so "oldest" is well defined
        fs::last_write_time(cache.pathFor(loc), fs::file_time_type::clock::now() +
                                                    std::chrono::seconds(&loc - frames.data()));
    }
    std::uint64_t total = 0;
    for (const auto& e : fs::directory_iterator(s.folder))
        total += e.file_size();
    EXPECT_LE(total, s.budgetBytes);
    EXPECT_TRUE(fs::exists(cache.pathFor(frames[3])));
    EXPECT_FALSE(fs::exists(cache.pathFor(frames[0])));
}

TEST(Dataset, UsesTheDiskCacheAndLoadsEachFrameOnceUnderContention) {
    TempDir dir;
    const std::string src = dir.write(
        "multi.dump", dumpFrame(0, 30, 0.0f) + dumpFrame(10, 30, 1.0f) + dumpFrame(20, 30, 2.0f));
    auto cache = std::make_shared<FrameCache>(settingsIn(dir));
    auto ds = Dataset::open({src});
    ds->setFrameCache(cache);
    std::vector<std::thread> threads;
    std::vector<std::shared_ptr<const Frame>> got(12);
    for (std::size_t t = 0; t < got.size(); ++t)
        threads.emplace_back([&, t] { got[t] = ds->frame(t % 3); });
    for (auto& t : threads)
        t.join();
    for (std::size_t t = 0; t < got.size(); ++t)
        EXPECT_EQ(got[t], got[t % 3]);    // one shared frame per index
    EXPECT_EQ(cache->stats().misses, 3u); // one load per frame, not one per thread
    EXPECT_EQ(cache->stats().writes, 3u);

    auto again = Dataset::open({src}); // a new session: frames come from the disk cache
    again->setFrameCache(cache);
    for (std::size_t k = 0; k < 3; ++k)
        expectIdentical(*ds->frame(k), *again->frame(k));
    EXPECT_EQ(cache->stats().hits, 3u);
}

TEST(Dataset, MemoryBudgetDefaultsToAQuarterOfRam) {
    const auto ram = static_cast<std::size_t>(::sysconf(_SC_PHYS_PAGES)) *
                     static_cast<std::size_t>(::sysconf(_SC_PAGE_SIZE));
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGE_SIZE));
    EXPECT_LE(defaultFrameMemoryBudget(), ram / 4);
    EXPECT_GT(defaultFrameMemoryBudget() + page, ram / 4);
    Dataset ds;
    EXPECT_EQ(ds.cacheBudget(), defaultFrameMemoryBudget());
    ds.setCacheBudget(12345);
    EXPECT_EQ(ds.cacheBudget(), 12345u);
}

TEST(Dataset, LoaderErrorsReachEveryWaiter) {
    auto ds = Dataset::fromLoader(2, [](std::size_t k) -> Frame {
        if (k == 1)
            throw std::runtime_error("frame one is broken");
        Frame f;
        f.finalize();
        return f;
    });
    EXPECT_EQ(ds->frame(0)->size(), 0u);
    EXPECT_THROW(ds->frame(1), std::runtime_error);
    EXPECT_THROW(ds->frame(1), std::runtime_error); // not cached as a success
    EXPECT_FALSE(ds->isCached(1));
}

TEST(Dataset, OpeningASeriesReportsEachFileAndCanBeCancelled) {
    TempDir dir;
    for (int k = 0; k < 4; ++k)
        dir.write("s.dump." + std::to_string(k), dumpFrame(k * 10, 5, float(k)));
    std::vector<double> heard;
    auto ds = Dataset::open({dir.file("s.dump.*")}, [&](double f) {
        heard.push_back(f);
        return true;
    });
    EXPECT_EQ(ds->frameCount(), 4u);
    EXPECT_EQ(heard, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
    int calls = 0;
    EXPECT_THROW(Dataset::open({dir.file("s.dump.*")}, [&](double) { return ++calls < 2; }),
                 OpenCancelled);
    EXPECT_EQ(calls, 2);
}
