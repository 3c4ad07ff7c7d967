#include "core/io/input_error.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "session_commands.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;
using faultline::test::TempDir;

namespace {

// Two frames of 8 spheres on a 2x2x2 lattice; strain = x + frame.
std::string writeCube(const TempDir& dir, const std::string& name) {
    std::string text;
    for (int t = 0; t < 2; ++t) {
        text += "ITEM: TIMESTEP\n" + std::to_string(t * 10) +
                "\nITEM: NUMBER OF ATOMS\n8\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
                "ITEM: ATOMS id x y z strain\n";
        int id = 1;
        for (int z = 0; z < 2; ++z)
            for (int y = 0; y < 2; ++y)
                for (int x = 0; x < 2; ++x)
                    text += std::to_string(id++) + " " + std::to_string(x) + " " +
                            std::to_string(y) + " " + std::to_string(z) + " " +
                            std::to_string(x + t) + "\n";
    }
    return dir.write(name, text);
}

using faultline::test::cmd;

} // namespace

TEST(SessionOpen, OpensASessionFileAsANewHistory) {
    TempDir dir;
    const std::string a = writeCube(dir, "a.dump"), b = writeCube(dir, "b.dump");
    // The session to open: data b, frame 1, a box and a threshold.
    {
        Session maker;
        maker.apply({{"op", "data.open"}, {"paths", {b}}});
        maker.apply(cmd(R"({"op":"frame.set","frame":1})"));
        maker.apply(cmd(R"({"op":"box.add","name":"half","min":[0,0,0],"max":[0.5,1,1]})"));
        maker.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":1,"high":1})"));
        saveSessionFile(maker.state(), dir.file("saved.faultline.json"));
    }
    Session s;
    s.setBaseDir(dir.path().string());
    s.apply({{"op", "data.open"}, {"paths", {a}}});
    s.apply(cmd(R"({"op":"box.add","name":"mine","min":[0,0,0],"max":[1,1,1],"mode":"cut"})"));
    const SessionState before = s.state();
    EXPECT_EQ(s.visibility().visibleCount, 0u);

    s.apply(cmd(R"({"op":"session.open","path":"saved.faultline.json"})"));
    EXPECT_EQ(s.state().dataPaths, std::vector<std::string>{b});
    EXPECT_EQ(s.state().frame, 1u);
    ASSERT_EQ(s.state().boxes.size(), 1u);
    EXPECT_EQ(s.state().boxes[0].name, "half");
    EXPECT_EQ(s.visibility().visibleCount, 4u); // x == 0 in the half box, strain 0 + 1 == 1

    // Issue 41: undo past the open emptied the workbench, and a save then wrote that over the
    // file. Opening starts a new history: nothing to undo, the opened state stays.
    EXPECT_FALSE(s.canUndo());
    EXPECT_FALSE(s.undo());
    EXPECT_THROW(s.apply(cmd(R"({"op":"undo"})")), CommandError);
    EXPECT_EQ(s.state().boxes[0].name, "half");
    EXPECT_FALSE(s.modified());
    // What comes after the open undoes back to it, and no further.
    s.apply(cmd(R"({"op":"box.remove","name":"half"})"));
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(s.visibility().visibleCount, 4u);
    EXPECT_FALSE(s.undo());
    EXPECT_NE(s.state(), before);
}

// Opening data is a new history too; what came before it is no longer undoable.
TEST(SessionOpen, OpeningDataStartsANewHistory) {
    TempDir dir;
    Session s;
    s.apply(cmd(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,1,1]})"));
    EXPECT_TRUE(s.canUndo());
    s.apply({{"op", "data.open"}, {"paths", {writeCube(dir, "a.dump")}}});
    EXPECT_FALSE(s.canUndo());
    EXPECT_FALSE(s.canRedo());
    EXPECT_EQ(s.undoLabel(), "");
}

TEST(SessionOpen, AMissingFileOrBadStateChangesNothing) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeCube(dir, "a.dump")}}});
    const SessionState before = s.state();
    EXPECT_THROW(s.apply({{"op", "session.open"}, {"path", dir.file("none.faultline.json")}}),
                 CommandError);
    EXPECT_THROW(s.apply(cmd(R"({"op":"session.open"})")), CommandError);
    EXPECT_THROW(s.apply(cmd(R"({"op":"session.restore","state":{"schema":1,"frame":"x"}})")),
                 CommandError);
    // A session whose data is gone.
    SessionState gone = before;
    gone.dataPaths = {dir.file("gone.dump")};
    EXPECT_THROW(s.apply({{"op", "session.restore"}, {"state", sessionToJson(gone, "")}}),
                 CommandError);
    // A frame the data does not have.
    SessionState far = before;
    far.frame = 5;
    EXPECT_THROW(s.apply({{"op", "session.restore"}, {"state", sessionToJson(far, "")}}),
                 CommandError);
    EXPECT_EQ(s.state(), before);
    EXPECT_EQ(s.undoDepth(), 0u); // the data.open started the history
}

TEST(SessionOpen, TheDatasetOpenerIsUsedForData) {
    TempDir dir;
    const std::string a = writeCube(dir, "a.dump");
    Session s;
    int calls = 0;
    auto prepared = Dataset::open({a});
    s.setDatasetOpener([&](const std::vector<std::string>& paths) {
        ++calls;
        EXPECT_EQ(paths, std::vector<std::string>{a});
        return prepared;
    });
    s.apply({{"op", "data.open"}, {"paths", {a}}});
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(s.dataset(), prepared);
}
