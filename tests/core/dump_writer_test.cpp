#include "core/data/dataset.hpp"
#include "core/synth/dump_writer.hpp"

#include "test_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace faultline::core;
using faultline::test::slurp;

namespace {

Frame sample(std::int64_t timestep, float shift) {
    Frame f;
    f.timestep = timestep;
    f.ids = {7, 3, 12};
    f.x = {0.1f + shift, -2.5f, 1e-3f};
    f.y = {1.0f, 2.0f, 3.0f};
    f.z = {123.456f, 0.0f, -0.333f};
    f.radius = {1.0f, 0.5f, 0.25f};
    AttributeColumn type;
    type.name = "type";
    type.type = ColumnType::Int32;
    type.ints = {1, 2, 1};
    AttributeColumn strain;
    strain.name = "strain";
    strain.floats = {0.0123f, 1.0f / 3.0f, 2.5e-7f};
    f.attributes = {type, strain};
    f.box.known = true;
    f.box.lo = {0, -1, 0};
    f.box.hi = {10.5, 4, 125};
    f.finalize();
    return f;
}

} // namespace

TEST(LammpsDumpWriter, WritesTheExactTextOfAFrame) {
    const faultline::test::TempDir dir;
    const std::string path = dir.file("one.lammpstrj");
    {
        LammpsDumpWriter w(path);
        w.write(sample(40, 0), {"id", "type", "x", "y", "z", "radius", "strain"});
        w.close();
    }
    EXPECT_EQ(slurp(path), "ITEM: TIMESTEP\n40\nITEM: NUMBER OF ATOMS\n3\n"
                           "ITEM: BOX BOUNDS ff ff ff\n0 10.5\n-1 4\n0 125\n"
                           "ITEM: ATOMS id type x y z radius strain\n"
                           "7 1 0.1 1 123.456 1 0.0123\n"
                           "3 2 -2.5 2 0 0.5 0.33333334\n"
                           "12 1 0.001 3 -0.333 0.25 2.5e-07\n");
}

TEST(LammpsDumpWriter, ReaderGetsEveryValueBackExactlyPlainAndGzip) {
    const faultline::test::TempDir dir;
    for (int level : {0, 6}) {
        const std::string path = dir.file(level ? "many.lammpstrj.gz" : "many.lammpstrj");
        const Frame a = sample(0, 0.0f), b = sample(100, 0.5f);
        {
            LammpsDumpWriter w(path, level);
            for (const Frame* f : {&a, &b})
                w.write(*f, {"id", "type", "x", "y", "z", "radius", "strain"});
            w.close();
        }
        auto ds = Dataset::open({path});
        ASSERT_EQ(ds->frameCount(), 2u);
        for (std::size_t k = 0; k < 2; ++k) {
            const Frame& want = k ? b : a;
            auto got = ds->frame(k);
            EXPECT_EQ(got->timestep, want.timestep);
            EXPECT_EQ(got->ids, want.ids);
            EXPECT_EQ(got->x, want.x);
            EXPECT_EQ(got->y, want.y);
            EXPECT_EQ(got->z, want.z);
            EXPECT_EQ(got->radius, want.radius);
            EXPECT_EQ(got->box.hi, want.box.hi);
            ASSERT_TRUE(got->attribute("strain"));
            EXPECT_EQ(got->attribute("strain")->floats, want.attribute("strain")->floats);
            ASSERT_TRUE(got->attribute("type"));
            EXPECT_EQ(got->attribute("type")->ints, want.attribute("type")->ints);
        }
    }
}

TEST(LammpsDumpWriter, UnwritablePathThrowsNamingIt) {
    try {
        LammpsDumpWriter w("/nonexistent-folder/x.lammpstrj");
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.lammpstrj"), std::string::npos);
    }
}
