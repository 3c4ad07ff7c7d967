// GzipReader: any offset of a gzip file read as reading in order gives it, through the access
// points a reader of the same file remembered; concatenated members, trailing garbage,
// truncated and corrupt files.
#include "core/io/byte_source.hpp"
#include "core/io/gzip_reader.hpp"
#include "core/io/input_error.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <atomic>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {
using faultline::core::ByteSource;
using faultline::core::InputError;
using faultline::core::readFileBytes;
using faultline::test::inputErrorOf;
using faultline::test::TempDir;
namespace detail = faultline::core::detail;

// Dump-like text: ids and numbers, compressible as a real dump is.
std::string dumpText(std::size_t lines, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 100);
    std::string text;
    char line[128];
    for (std::size_t i = 0; i < lines; ++i) {
        std::snprintf(line, sizeof line, "%zu 1 %.6f %.6f %.6f 0.5\n", i + 1, u(rng), u(rng),
                      u(rng));
        text += line;
    }
    return text;
}

std::string gzipped(const std::string& text, int level) {
    z_stream s{};
    EXPECT_EQ(deflateInit2(&s, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&s, uLong(text.size())), '\0');
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    s.avail_in = uInt(text.size());
    s.next_out = reinterpret_cast<Bytef*>(out.data());
    s.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&s, Z_FINISH), Z_STREAM_END);
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

// Small spacing, so that files of a few MB hold many access points; each test starts afresh.
class GzipReaderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        detail::clearGzipIndexes();
        detail::setGzipIndexSpacing(64 << 10);
    }
    void TearDown() override {
        detail::setGzipIndexSpacing(0);
        detail::clearGzipIndexes();
    }
};

std::string readAll(ByteSource& source) {
    std::string all;
    char buffer[70000]; // not a multiple of anything deflate uses
    while (const std::size_t got = source.read(buffer, sizeof buffer))
        all.append(buffer, got);
    return all;
}

TEST_F(GzipReaderTest, AnyOffsetReadsAsInOrder) {
    TempDir dir;
    // Members (as `cat a.gz b.gz` or a dump appended to): levels 9 and 1, an empty one, and a
    // stored one.
    const std::string a = dumpText(40000, 1), b = dumpText(30000, 2), c = dumpText(3000, 3);
    const std::string text = a + b + c;
    const std::string path =
        dir.write("run.dump.gz", gzipped(a, 9) + gzipped(b, 1) + gzipped("", 6) + gzipped(c, 0));
    {
        ByteSource first(path);
        ASSERT_TRUE(first.compressed());
        ASSERT_EQ(readAll(first), text);
    }
    const std::size_t points = detail::gzipAccessPoints(path);
    EXPECT_GE(points, text.size() / (64 << 10) / 2) << "the first read remembers access points";
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::uint64_t> at(0, text.size());
    ByteSource source(path);
    for (int k = 0; k < 60; ++k) { // forwards and backwards, within and across members
        const std::uint64_t offset = k == 0 ? a.size() : k == 1 ? a.size() + b.size() : at(rng);
        const std::size_t length = std::size_t(at(rng) % 100000);
        source.seek(offset);
        std::string got(length, '\0');
        got.resize(source.read(got.data(), length));
        ASSERT_EQ(got, text.substr(offset, length)) << "at " << offset;
        EXPECT_EQ(source.position(), offset + got.size());
    }
    // Ranges as the readers take a frame's bytes, each through a new source.
    for (std::uint64_t offset : {std::uint64_t(0), std::uint64_t(a.size() - 5),
                                 std::uint64_t(text.size() / 2), std::uint64_t(text.size() - 9)})
        EXPECT_EQ(readFileBytes(path, offset, 9), text.substr(offset, 9));
    source.seek(text.size() + 10); // past the end: reads give nothing
    char byte;
    EXPECT_EQ(source.read(&byte, 1), 0u);
}

TEST_F(GzipReaderTest, ASeekFirstStillFindsItsWay) {
    // No reader went through the file before: the seek inflates from the start, and remembers.
    TempDir dir;
    const std::string text = dumpText(50000, 4);
    const std::string path = dir.write("a.gz", gzipped(text, 6));
    EXPECT_EQ(readFileBytes(path, text.size() - 100, 100), text.substr(text.size() - 100));
    EXPECT_GT(detail::gzipAccessPoints(path), 10u);
    EXPECT_EQ(readFileBytes(path, 12345, 1000), text.substr(12345, 1000));
}

TEST_F(GzipReaderTest, ReadersOnSeveralThreadsShareTheAccessPoints) {
    // As the prefetcher loads frames: each thread its own sources, one index for the file,
    // filled by whichever gets somewhere first.
    TempDir dir;
    const std::string text = dumpText(60000, 10);
    const std::string path = dir.write("a.gz", gzipped(text, 6));
    std::atomic<int> wrong{0};
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            std::mt19937 rng(t);
            std::uniform_int_distribution<std::uint64_t> at(0, text.size() - 1);
            for (int k = 0; k < 15; ++k) {
                const std::uint64_t offset = at(rng);
                const std::uint64_t length = std::min<std::uint64_t>(5000, text.size() - offset);
                if (readFileBytes(path, offset, length) != text.substr(offset, length))
                    ++wrong;
            }
        });
    for (auto& t : threads)
        t.join();
    EXPECT_EQ(wrong.load(), 0);
    EXPECT_GT(detail::gzipAccessPoints(path), 10u);
}

TEST_F(GzipReaderTest, TrailingGarbageAfterTheLastMemberIsIgnored) {
    TempDir dir;
    const std::string text = dumpText(20000, 5);
    const std::string path = dir.write("a.gz", gzipped(text, 6) + "not gzip at all\n");
    ByteSource source(path);
    EXPECT_EQ(readAll(source), text);
    EXPECT_EQ(readFileBytes(path, text.size() - 10, 10), text.substr(text.size() - 10));
}

TEST_F(GzipReaderTest, TruncatedAndCorruptFilesAreErrorsWithTheirOffset) {
    TempDir dir;
    const std::string text = dumpText(50000, 6);
    const std::string whole = gzipped(text, 6);
    const std::string cut = dir.write("cut.gz", whole.substr(0, whole.size() / 2));
    std::string message = inputErrorOf([&] {
        ByteSource source(cut);
        readAll(source);
    });
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_NE(message.find("cut.gz"), std::string::npos) << message;
    // Again through the access points the first attempt left.
    message = inputErrorOf([&] { readFileBytes(cut, text.size() - 10, 10); });
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;

    std::string bad = whole;
    for (std::size_t k = bad.size() / 3; k < bad.size() / 3 + 64; ++k)
        bad[k] = char(~bad[k]);
    const std::string corrupt = dir.write("bad.gz", bad);
    message = inputErrorOf([&] {
        ByteSource source(corrupt);
        readAll(source);
    });
    EXPECT_NE(message.find("corrupt compressed data"), std::string::npos) << message;
    EXPECT_NE(message.find("byte"), std::string::npos) << message;

    const std::string header = dir.write("header.gz", whole.substr(0, 6));
    message = inputErrorOf([&] {
        ByteSource source(header);
        readAll(source);
    });
    EXPECT_FALSE(message.empty());
}

TEST_F(GzipReaderTest, ARewrittenFileGetsANewIndex) {
    TempDir dir;
    const std::string one = dumpText(30000, 8), two = dumpText(30000, 9);
    const std::string path = dir.write("a.gz", gzipped(one, 6));
    EXPECT_EQ(readFileBytes(path, 500000, 50), one.substr(500000, 50));
    dir.write("a.gz", gzipped(two + "x", 6)); // another size: other access points
    EXPECT_EQ(readFileBytes(path, 500000, 50), two.substr(500000, 50));
}

} // namespace
