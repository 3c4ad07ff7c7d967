#include "core/faults/candidates.hpp"
#include "core/io/input_error.hpp"
#include "core/session/command_label.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/journal.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "core/surface/fault_surface.hpp"
#include "lattice_dump.hpp"
#include "session_commands.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

#include <set>

#include <filesystem>
#include <fstream>

using namespace faultline::core;
using faultline::test::TempDir;

namespace {

// See lattice_dump.hpp.
std::string writeLattice(const TempDir& dir) {
    return dir.write("lattice.dump", faultline::test::latticeDump());
}

using faultline::test::cmd;

// `text` is refused with a CommandError whose message holds `message`.
void expectRefused(Session& s, const char* text, const std::string& message) {
    try {
        s.apply(cmd(text));
        ADD_FAILURE() << "accepted " << text;
    } catch (const CommandError& e) {
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
}

// The lattice with only two walls visible, x = 0 and x = 3 (16 spheres each, three spacings apart).
void openTwoWalls(Session& s, const TempDir& dir) {
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(Json::parse(R"({"op":"box.add","name":"west","min":[0,0,0],"max":[0,3,3]})"));
    s.apply(Json::parse(R"({"op":"box.add","name":"east","min":[3,0,0],"max":[3,3,3]})"));
}

// States compared through their saved form, so a failure prints a readable difference.
std::string dump(const SessionState& s) { return sessionToJson(s, "").dump(); }

} // namespace

TEST(Session, BoxesThresholdsAndFaultFilterGiveExactVisibleCounts) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    EXPECT_EQ(s.visibility().visibleCount, 64u);
    s.apply(cmd(R"({"op":"box.add","name":"low","min":[0,0,0],"max":[3,3,1],"mode":"keep"})"));
    EXPECT_EQ(s.visibility().visibleCount, 32u); // z in {0, 1}, bounds inclusive
    s.apply(cmd(R"({"op":"box.add","name":"hole","min":[0,0,0],"max":[0,3,3],"mode":"cut"})"));
    EXPECT_EQ(s.visibility().visibleCount, 24u); // minus x == 0
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":0.5,"high":1e30})"));
    EXPECT_EQ(s.visibility().visibleCount, 16u); // x in {2, 3}
    s.apply(cmd(R"({"op":"box.set","name":"hole","enabled":false})"));
    EXPECT_EQ(s.visibility().visibleCount, 16u);
    s.apply(cmd(R"({"op":"threshold.set","variable":"strain","low":0.3})"));
    EXPECT_EQ(s.visibility().visibleCount, 24u); // x in {1, 2, 3}
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    EXPECT_EQ(s.state().fault("F1")->ids.size(), 24u);
    s.apply(cmd(R"({"op":"threshold.remove","variable":"strain"})"));
    s.apply(cmd(R"({"op":"box.remove","name":"low"})"));
    EXPECT_EQ(s.visibility().visibleCount, 64u);
    s.apply(cmd(R"({"op":"fault.filter","mode":"labelled"})"));
    EXPECT_EQ(s.visibility().visibleCount, 24u);
    s.apply(cmd(R"({"op":"fault.filter","mode":"all"})"));
    s.apply(cmd(R"({"op":"fault.set","name":"F1","visible":false})"));
    EXPECT_EQ(s.visibility().visibleCount, 40u);
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    EXPECT_EQ(s.visibility().visibleCount, 40u); // labels follow ids across frames
}

TEST(Session, EveryOpUndoesAndRedoesExactly) {
    TempDir dir;
    const std::string data = writeLattice(dir);
    Session s;
    const std::vector<Json> commands = {
        {{"op", "data.open"}, {"paths", {data}}},
        cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"),
        cmd(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[2,2,2],"mode":"cut","index":0})"),
        cmd(R"({"op":"box.set","name":"a","max":[3,3,3],"mode":"cut","rename":"a2"})"),
        cmd(R"({"op":"box.remove","name":"b"})"),
        cmd(R"({"op":"threshold.add","variable":"strain","low":0,"high":2})"),
        cmd(R"({"op":"threshold.add","variable":"layer","low":1,"high":2,"index":0})"),
        cmd(R"({"op":"threshold.set","variable":"strain","high":1.5,"enabled":false})"),
        cmd(R"({"op":"threshold.remove","variable":"layer"})"),
        cmd(R"({"op":"fault.create","name":"F1","ids":[5,3,1,3]})"),
        cmd(R"({"op":"fault.create","name":"F2","ids":[10,11],"color":[0,1,0],"notes":"n"})"),
        cmd(R"({"op":"fault.add","name":"F1","ids":[2,3,4]})"),
        cmd(R"({"op":"fault.remove","name":"F1","ids":[1,99]})"),
        cmd(R"({"op":"fault.set","name":"F1","color":[0.1,0.2,0.3],"notes":"antithetic","rename":"F1b"})"),
        cmd(R"({"op":"fault.filter","mode":"only","fault":"F2"})"),
        cmd(R"({"op":"fault.delete","name":"F2"})"),
        cmd(R"({"op":"fault.create","name":"F3","ids":[40]})"),
        cmd(R"({"op":"fault.merge","names":["F1b","F3"],"into":"M"})"),
        cmd(R"({"op":"view.add","name":"right","frame":2})"),
        cmd(R"({"op":"view.set","name":"right","offset":-1})"),
        cmd(R"({"op":"view.set","name":"right","context_points":true})"),
        cmd(R"({"op":"color.set","view":"main","variable":"strain","map":"viridis","range":[0,0.5]})"),
        cmd(R"({"op":"color.set","view":"main","difference":"change","since_offset":-1})"),
        cmd(R"({"op":"color.set","view":"main","difference":"displacement","since_frame":0})"),
        cmd(R"({"op":"layout.set","layout":{"split":"h"}})"),
        cmd(R"({"op":"view.remove","name":"right"})"),
        cmd(R"({"op":"data.close"})"),
    };
    std::vector<SessionState> states{s.state()};
    for (const auto& c : commands) {
        s.apply(c);
        states.push_back(s.state());
    }
    EXPECT_EQ(s.state().fault("M")->ids, (std::vector<std::int64_t>{2, 3, 4, 5, 40}));
    // data.open (the first command) starts the history: undo walks back to just after it.
    for (std::size_t k = commands.size(); k > 1; --k) {
        ASSERT_TRUE(s.undo());
        EXPECT_EQ(dump(s.state()), dump(states[k - 1])) << "undo of " << commands[k - 1].dump();
        EXPECT_EQ(s.state(), states[k - 1]);
    }
    EXPECT_FALSE(s.undo());
    for (std::size_t k = 1; k < commands.size(); ++k) {
        ASSERT_TRUE(s.redo());
        EXPECT_EQ(dump(s.state()), dump(states[k + 1])) << "redo of " << commands[k].dump();
    }
    EXPECT_FALSE(s.redo());
}

// Issue 27: time is view state (as in OVITO and ParaView). Moving through frames makes no undo
// step and keeps what redo would repeat; undo and redo say what they revert.
TEST(Session, FramesAreNoUndoStepsAndUndoSaysWhatItReverts) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":0.5,"high":1e30})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2]})"));
    s.apply(cmd(R"({"op":"fault.add","name":"F1","from":"visible"})")); // x in {2, 3}: 32 spheres
    EXPECT_EQ(s.undoLabel(), "add 32 spheres to F1");
    const std::size_t depth = s.undoDepth();
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    s.apply(cmd(R"({"op":"frame.set","frame":1})"));
    EXPECT_EQ(s.undoDepth(), depth);
    EXPECT_EQ(s.undoLabel(), "add 32 spheres to F1");
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(s.state().frame, 1u); // the frame stays where the user went
    EXPECT_EQ(s.state().fault("F1")->ids.size(), 2u);
    EXPECT_EQ(s.redoLabel(), "add 32 spheres to F1");
    EXPECT_EQ(s.undoLabel(), "make fault F1 (2 spheres)");
    s.apply(cmd(R"({"op":"frame.set","frame":0})"));
    EXPECT_EQ(s.redoLabel(), "add 32 spheres to F1"); // still there
    ASSERT_TRUE(s.redo());
    EXPECT_EQ(s.state().fault("F1")->ids.size(), 34u);
    s.apply(cmd(R"({"op":"threshold.set","variable":"strain","low":0.7})"));
    EXPECT_EQ(s.undoLabel(), "change the strain threshold");
    EXPECT_EQ(s.redoLabel(), "");
    s.apply(cmd(R"({"op":"batch","commands":[{"op":"fault.delete","name":"F1"}]})"));
    EXPECT_EQ(s.undoLabel(), "delete F1");
    // Nothing unsaved to ask about after only moving through time.
    s.markSaved();
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    EXPECT_FALSE(s.modified());
    s.apply(cmd(R"({"op":"threshold.set","variable":"strain","low":0.6})"));
    s.apply(cmd(R"({"op":"frame.set","frame":1})"));
    EXPECT_TRUE(s.modified());
}

// Issue 42 (a walkthrough): four undos and four redos back to the saved state still asked to
// save; undoing back to it leaves the session unmodified too, and opening is saved.
TEST(Session, UndoAndRedoBackToTheSavedStateLeaveItUnmodified) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    EXPECT_TRUE(s.modified());
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2]})"));
    s.apply(cmd(R"({"op":"fault.add","name":"F1","ids":[3]})"));
    const std::string path = dir.file("a.faultline.json");
    s.apply({{"op", "session.save"}, {"path", path}});
    EXPECT_FALSE(s.modified());
    s.undo(), s.undo();
    EXPECT_TRUE(s.modified());
    s.redo();
    EXPECT_TRUE(s.modified());
    s.redo();
    EXPECT_FALSE(s.modified()); // back where it was saved
    s.apply(cmd(R"({"op":"fault.add","name":"F1","ids":[4]})"));
    EXPECT_TRUE(s.modified());
    s.undo();
    EXPECT_FALSE(s.modified());
    s.undo();
    s.apply(cmd(R"({"op":"fault.add","name":"F1","ids":[5]})")); // another branch
    EXPECT_TRUE(s.modified());
    Session o;
    o.apply({{"op", "session.open"}, {"path", path}});
    EXPECT_FALSE(o.modified());
    o.apply(cmd(R"({"op":"fault.add","name":"F1","ids":[6]})"));
    o.undo();
    EXPECT_FALSE(o.modified());
}

// Issue 41, item 7: camera moves are view state like time: no undo step
// (the first Ctrl+Z after a rectangle undid a camera move), nothing unsaved to ask about; the
// status says what failed in words.
TEST(Session, CameraMovesAreNoUndoSteps) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(
        R"({"op":"layout.set","layout":{"root":{"split":"h","ratio":0.2,"first":{"tabs":["data","faults"],"active":"data"},"second":{"tabs":["viewports"]}}}})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2]})"));
    s.markSaved();
    s.apply(cmd(R"({"op":"camera.set","view":"main","azimuth":30,"distance":12})"));
    EXPECT_FALSE(s.modified());
    EXPECT_EQ(s.undoLabel(), "make fault F1 (2 spheres)");
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(s.state().fault("F1"), nullptr);
    EXPECT_EQ(s.state().view("main")->camera.azimuth, 30); // the camera stays where it went
    // Nor does a click on a tab or a splitter drag: redo keeps what it would bring back.
    s.apply(cmd(
        R"({"op":"layout.set","layout":{"root":{"split":"h","ratio":0.3,"first":{"tabs":["data","faults"],"active":"faults"},"second":{"tabs":["viewports"]}}}})"));
    EXPECT_TRUE(s.canRedo());
    EXPECT_EQ(s.redoLabel(), "make fault F1 (2 spheres)");
    EXPECT_EQ(describeFailure(cmd(R"({"op":"threshold.set","variable":"strain","low":2,"high":1})"),
                              "threshold.set: low must not exceed high"),
              "Could not change the strain threshold: low must not exceed high");
    EXPECT_EQ(describeFailure(cmd(R"({"op":"undo"})"), "undo: nothing to undo"), "Nothing to undo");
    // A batch fails with the message of the command in it that failed: its op's name goes too.
    EXPECT_EQ(
        describeFailure(
            cmd(R"({"op":"batch","commands":[{"op":"threshold.set","variable":"strain","low":2}]})"),
            "threshold.set: low must not exceed high"),
        "Could not " +
            describeCommand(cmd(
                R"({"op":"batch","commands":[{"op":"threshold.set","variable":"strain","low":2}]})")) +
            ": low must not exceed high");
    EXPECT_EQ(describeCommand(cmd(R"({"op":"layout.set","layout":{}})")), "rearrange the panels");
}

TEST(Session, DifferenceColouringIsSavedAndItsReferenceFrameResolves) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    s.apply(cmd(
        R"({"op":"color.set","view":"main","variable":"strain","difference":"change","since_offset":-1})"));
    const ViewState& v = *s.state().view("main");
    EXPECT_EQ(v.difference.mode, ColorDifference::Mode::Change);
    EXPECT_EQ(s.referenceFrameOfView(v), 1u);
    EXPECT_EQ(colorTitle(v, 1), "strain change since frame 1");
    s.apply(cmd(R"({"op":"color.set","view":"main","since_offset":-10})"));
    EXPECT_EQ(s.referenceFrameOfView(*s.state().view("main")), 0u); // clamped to the data
    const std::string file = dir.file("d.faultline.json");
    saveSessionFile(s.state(), file);
    EXPECT_EQ(loadSessionFile(file).views, s.state().views);
    for (const char* bad : {R"({"op":"color.set","difference":"ratio"})",
                            R"({"op":"color.set","since_frame":1,"since_offset":-1})",
                            R"({"op":"color.set","since_frame":-1})",
                            R"({"op":"color.set","variable":"","difference":"change"})"})
        EXPECT_THROW(s.apply(Json::parse(bad)), CommandError) << bad;
    EXPECT_EQ(s.state().view("main")->difference.reference, (FrameBinding{true, -10}));
}

TEST(Session, ASessionOpensWithItsDataAtAnotherPlace) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    const std::string file = dir.file("s.faultline.json");
    saveSessionFile(s.state(), file);
    std::filesystem::create_directories(dir.file("moved"));
    std::filesystem::rename(dir.file("lattice.dump"), dir.file("moved/lattice.dump"));
    Session t;
    try {
        t.apply({{"op", "session.open"}, {"path", file}});
        ADD_FAILURE() << "opened a session whose data is gone";
    } catch (const CommandError& e) {
        EXPECT_NE(std::string(e.what()).find("lattice.dump"), std::string::npos) << e.what();
    }
    t.apply({{"op", "session.open"}, {"path", file}, {"data", {dir.file("moved/lattice.dump")}}});
    ASSERT_NE(t.dataset(), nullptr);
    EXPECT_EQ(t.state().box("a")->max, (std::array<double, 3>{1, 1, 1}));
    EXPECT_EQ(t.state().dataPaths, (std::vector<std::string>{dir.file("moved/lattice.dump")}));
}

TEST(Session, FaultTracksFollowEachFaultThroughTimeAsCsv) {
    TempDir dir;
    Session s;
    openTwoWalls(s, dir); // W is the west wall but one sphere
    std::vector<std::int64_t> west;
    for (std::int64_t id = 5; id <= 64; id += 4)
        west.push_back(id);
    s.apply({{"op", "fault.create"}, {"name", "W"}, {"ids", west}});
    s.apply({{"op", "export.csv"},
             {"what", "fault_tracks"},
             {"path", dir.file("t.csv")},
             {"min_size", 5}});
    std::ifstream in(dir.file("t.csv"));
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);)
        lines.push_back(l);
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0],
              "frame,fault,present,candidate,candidate_size,shared,jaccard,precision,recall");
    // Candidates tie at 16: the one with the smaller ids (west, id 1) comes first.
    EXPECT_EQ(lines[1], "0,W,15,0,16,15,0.9375,0.9375,1");
    EXPECT_EQ(lines[3], "2,W,15,0,16,15,0.9375,0.9375,1");
    EXPECT_THROW(s.apply({{"op", "export.csv"},
                          {"what", "fault_tracks"},
                          {"path", dir.file("u.csv")},
                          {"link", 0}}),
                 CommandError);
}

TEST(Session, RejectedCommandsChangeNothing) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    const SessionState before = s.state();
    const std::uint64_t version = s.version();
    auto rejects = [&](const char* text, const char* message) {
        try {
            s.apply(Json::parse(text));
            ADD_FAILURE() << "accepted " << text;
        } catch (const CommandError& e) {
            EXPECT_EQ(std::string(e.what()), message);
        }
        EXPECT_EQ(s.state(), before);
    };
    rejects(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})",
            "box.add: a box named \"a\" exists already");
    rejects(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,-1,1]})",
            "box.add: min must not exceed max on any axis");
    rejects(R"({"op":"box.add","name":"b","min":[0,0],"max":[1,1,1]})",
            "box.add: \"min\" must be an array of 3 numbers, found [0,0]");
    rejects(R"({"op":"box.set","name":"a","mode":"slice"})",
            "box.set: \"mode\" must be keep or cut, found \"slice\"");
    rejects(R"({"op":"box.set","name":"a","colour":1})",
            "box.set: unknown field \"colour\" (expected name, min, max, mode, enabled, rename)");
    rejects(R"({"op":"frame.set","frame":3})", "frame.set: frame 3 out of range 0..2");
    rejects(R"({"op":"threshold.add","variable":"strain","low":2,"high":1})",
            "threshold.add: low must not exceed high");
    rejects(R"({"op":"fault.add","name":"nope","ids":[1]})", "fault.add: no fault named \"nope\"");
    rejects(R"({"op":"fault.create","name":"F","ids":[1.5]})",
            "fault.create: \"ids\" must hold whole numbers, found 1.5");
    rejects(R"({"op":"fault.merge","names":["x","y"],"into":"z"})",
            "fault.merge: no fault named \"x\"");
    rejects(R"({"op":"view.remove","name":"main"})",
            "view.remove: the main view cannot be removed");
    rejects(R"({"op":"color.set","map":"rainbow"})",
            "color.set: \"map\" names no colour map (blue-red, viridis, diverging, pastel, bands, "
            "gray), found \"rainbow\"");
    // color.set reads and checks through the view codec: its rules are a session file's.
    rejects(R"({"op":"color.set","range":[2,1]})", "color.set: color.range must have low < high");
    rejects(R"({"op":"color.set","range_mode":"al"})",
            "color.set: \"range_mode\" must be frame, all, fixed or percentile, found \"al\"");
    rejects(R"({"op":"color.set","variable":"","difference":"change"})",
            "color.set: color.difference.mode change needs a variable");
    rejects(R"({"op":"data.open","paths":["/nonexistent/file.dump"]})",
            "data.open: /nonexistent/file.dump: cannot open: No such file or directory");
    rejects(R"({"op":"warp"})", "unknown op \"warp\"");
    rejects(R"({"op":"undo","steps":2})", "undo: unknown field \"steps\" (expected none)");
    rejects(R"({"op":"surface.build","fault":"F1"})", "surface.build: no fault named \"F1\"");
    EXPECT_EQ(s.version(), version);
}

TEST(Session, FailedBatchRollsBack) {
    Session s;
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    const SessionState before = s.state();
    EXPECT_THROW(
        s.apply(cmd(
            R"({"op":"batch","commands":[{"op":"box.remove","name":"a"},{"op":"box.remove","name":"zz"}]})")),
        CommandError);
    EXPECT_EQ(s.state(), before);
}

TEST(Session, NewCommandClearsRedo) {
    Session s;
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_TRUE(s.canRedo());
    s.apply(cmd(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,1,1]})"));
    EXPECT_FALSE(s.canRedo());
    EXPECT_EQ(s.journal().size(), 3u);
}

// A background export holds its place in the journal from when it was asked for: commands given
// while it ran come after it, so a replay exports the state it read. A failed one leaves no line.
TEST(Session, BackgroundActionsKeepTheirPlaceInTheJournal) {
    Session s;
    std::vector<std::string> sunk, held;
    s.setJournalSink(
        [&](const Json& c) {
            sunk.push_back(c.value("op", "") + ":" + c.value("name", c.value("path", "")));
        },
        [&](const Json& c) { held.push_back(c.value("op", "")); });
    const auto vdb = s.reserveAction();
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    const auto csv = s.reserveAction();
    s.apply(cmd(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,1,1]})"));
    EXPECT_TRUE(sunk.empty());
    EXPECT_EQ(held, (std::vector<std::string>{"box.add", "box.add"})); // at once, for crash safety
    EXPECT_EQ(s.pendingActions(), 2u);
    EXPECT_EQ(s.state().boxes.size(), 2u); // the commands themselves ran at once
    // The later export ends first: it waits for the one before it.
    s.settleAction(csv, cmd(R"({"op":"export.csv","what":"faults","path":"f.csv"})"));
    EXPECT_TRUE(sunk.empty());
    s.settleAction(vdb, cmd(R"({"op":"export.vdb","fault":"F1","path":"F1.vdb"})"));
    EXPECT_EQ(sunk, (std::vector<std::string>{"export.vdb:F1.vdb", "box.add:a", "export.csv:f.csv",
                                              "box.add:b"}));
    EXPECT_EQ(s.journal().size(), 4u);
    // One that fails records nothing; what waited behind it is written then.
    const auto failed = s.reserveAction();
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(sunk.size(), 4u);
    s.dropAction(failed);
    EXPECT_EQ(sunk.back(), "undo:");
    EXPECT_EQ(s.pendingActions(), 0u);
    // Only actions settle a place; shutting down gives up what is left.
    const auto wrong = s.reserveAction();
    EXPECT_THROW(s.settleAction(wrong, cmd(R"({"op":"box.remove","name":"a"})")), CommandError);
    s.apply(cmd(R"({"op":"box.remove","name":"a"})"));
    s.dropPendingActions();
    EXPECT_EQ(sunk.back(), "box.remove:a");
    EXPECT_EQ(s.journal().size(), 6u);
}

// The issue's other surface source: the visible spheres, named "*visible" where a fault's name
// goes. It follows thresholds (and boxes, time); no fault may take the name.
TEST(Session, TheVisibleSpheresHaveASurfaceOfTheirOwn) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":0.5,"high":9})")); // x >= 2
    ASSERT_EQ(s.visibility().visibleCount, 32u);
    s.apply(cmd(
        R"({"op":"surface.build","fault":"*visible","kernel":"compact","voxel":0.25,"iso":0.5})"));
    ASSERT_NE(s.state().surface("*visible"), nullptr);
    s.apply({{"op", "export.vdb"}, {"fault", "*visible"}, {"path", dir.file("out/visible.vdb")}});
    s.apply(
        {{"op", "export.gltf"}, {"faults", {"*visible"}}, {"path", dir.file("out/visible.glb")}});
    EXPECT_GT(std::filesystem::file_size(dir.file("out/visible.vdb")), 1000u);
    EXPECT_GT(std::filesystem::file_size(dir.file("out/visible.glb")), 1000u);
    // Saved and restored like a fault's surface.
    const std::string file = dir.file("out/v.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    EXPECT_EQ(loadSessionFile(file), s.state());
    auto rejects = [&](const char* text, const std::string& message) {
        expectRefused(s, text, message);
    };
    rejects(R"({"op":"fault.create","name":"*visible","from":"visible"})",
            "names the visible spheres' surface");
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2]})"));
    rejects(R"({"op":"fault.set","name":"F1","rename":"*visible"})", "cannot rename");
    // Nothing visible: refused before any work, saying why.
    s.apply(cmd(R"({"op":"threshold.set","variable":"strain","low":50,"high":60})"));
    rejects(R"({"op":"surface.build","fault":"*visible","iso":0.4})", "empty sphere set");
    rejects(R"({"op":"export.vdb","fault":"*visible","path":"x.vdb"})", "empty sphere set");
}

// Figure 4 with a variable: the spheres take a colour map of it, the voxels within radius +
// color_reach their average. On the lattice (strain = x / 3 at frame 0) the surface darkens
// towards x = 0 in the gray map; the settings undo, save and refuse bad values like the others.
TEST(Session, ASurfaceTakesItsSpheresColoursFromAVariable) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(
        cmd(R"({"op":"surface.build","fault":"F1","kernel":"compact","voxel":0.25,"iso":0.5})"));
    const SurfaceSettings plain = *s.state().surface("F1");
    s.apply(cmd(
        R"({"op":"surface.set","fault":"F1","color_by":"strain","map":"gray","range":[0,1],"color_reach":1.0})"));
    const SurfaceSettings byStrain = *s.state().surface("F1");
    EXPECT_EQ(byStrain.colorBy, "strain");
    const auto frame = s.currentFrame();
    const SurfaceResult r = buildFaultSurface(*frame, {*s.state().fault("F1"), byStrain});
    double west = 0, east = 0;
    int nw = 0, ne = 0;
    for (std::size_t v = 0; v < r.mesh.positions.size(); ++v) {
        const double grey = r.mesh.colors[v][0];
        EXPECT_NEAR(r.mesh.colors[v][1], grey, 1e-3); // a gray map: r = g = b
        if (r.mesh.positions[v][0] < 0.3)
            west += grey, ++nw;
        else if (r.mesh.positions[v][0] > 2.7)
            east += grey, ++ne;
    }
    ASSERT_GT(nw, 0);
    ASSERT_GT(ne, 0);
    EXPECT_GT(east / ne - west / nw, 0.5) << west / nw << " vs " << east / ne;
    // Its own cache entry: colours are part of the key.
    const SurfaceParams params = surfaceParamsOf(byStrain, *s.state().fault("F1"));
    EXPECT_NE(surfaceKeyOf(0, nullptr, *s.state().fault("F1"), byStrain, params).members,
              surfaceKeyOf(0, nullptr, *s.state().fault("F1"), plain, params).members);
    // Saved and restored; undone to the fault's plain colour.
    const std::string file = dir.file("c.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    EXPECT_EQ(loadSessionFile(file), s.state());
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(*s.state().surface("F1"), plain);
    // Deleting the fault and undoing that keeps the colouring.
    s.apply(cmd(R"({"op":"redo"})"));
    s.apply(cmd(R"({"op":"fault.delete","name":"F1"})"));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(*s.state().surface("F1"), byStrain);
    auto rejects = [&](const char* text, const std::string& message) {
        expectRefused(s, text, message);
    };
    rejects(R"({"op":"surface.build","fault":"F1","color_by":"nope"})", "no variable \"nope\"");
    rejects(R"({"op":"surface.set","fault":"F1","range":[1,0]})", "\"range\" must be [low, high]");
    rejects(R"({"op":"surface.set","fault":"F1","initial_color":[2,0,0]})", "\"initial_color\"");
    rejects(R"({"op":"surface.set","fault":"F1","map":"rainbow"})", "\"map\" names no colour map");
    rejects(R"({"op":"surface.set","fault":"F1","color_reach":-1})",
            "\"color_reach\" must be >= 0");
    // A reach that would make every voxel average every sphere is refused before any work.
    rejects(R"({"op":"surface.build","fault":"F1","color_reach":1e9})", "colour reach");
    EXPECT_EQ(*s.state().surface("F1"), byStrain);
    // One name per map: "grey" is stored as "gray" (one cache entry, not two).
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","map":"grey"})"));
    EXPECT_EQ(colorMapName(s.state().surface("F1")->colorMap), "gray");
}

// Issue 41: a surface in its fault's colour was hard to see among the fault's spheres. "color"
// gives the surface one colour of its own: every vertex takes it, the cache tells it apart, it
// is saved, undone, refused out of range, and a colouring by a variable takes over from it.
TEST(Session, ASurfaceTakesAColourOfItsOwn) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(
        cmd(R"({"op":"surface.build","fault":"F1","kernel":"compact","voxel":0.25,"iso":0.5})"));
    const SurfaceSettings plain = *s.state().surface("F1");
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","color":[0.1,0.9,0.2]})"));
    const SurfaceSettings own = *s.state().surface("F1");
    const Fault& f1 = *s.state().fault("F1");
    const SurfaceResult r = buildFaultSurface(*s.currentFrame(), {f1, own});
    ASSERT_FALSE(r.mesh.colors.empty());
    for (const auto& c : r.mesh.colors) {
        EXPECT_NEAR(c[0], 0.1f, 1e-4f);
        EXPECT_NEAR(c[1], 0.9f, 1e-4f);
        EXPECT_NEAR(c[2], 0.2f, 1e-4f);
    }
    const SurfaceParams params = surfaceParamsOf(own, f1);
    EXPECT_NE(surfaceKeyOf(0, nullptr, f1, own, params).members,
              surfaceKeyOf(0, nullptr, f1, plain, surfaceParamsOf(plain, f1)).members);
    const std::string file = dir.file("own.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    EXPECT_EQ(loadSessionFile(file), s.state());
    expectRefused(s, R"({"op":"surface.set","fault":"F1","color":[0,0,1.5]})", "\"color\"");
    // Coloured by a variable, the own colour no longer applies (the map does).
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","color_by":"strain","map":"gray"})"));
    const SurfaceResult byStrain =
        buildFaultSurface(*s.currentFrame(), {f1, *s.state().surface("F1")});
    for (const auto& c : byStrain.mesh.colors)
        EXPECT_NEAR(c[0], c[1], 1e-3f); // gray
    s.apply(cmd(R"({"op":"undo"})"));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(*s.state().surface("F1"), plain);
}

// JOURNAL.md: surface.build without "iso" (or with "iso":"wrap") takes the iso-value that wraps
// the fault's spheres, as a new surface in the workbench does; an explicit number is kept.
TEST(Session, ASurfaceBuiltWithoutAnIsoValueWrapsItsSpheres) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","kernel":"inverse","voxel":0.25})"));
    SurfaceSettings expected = *s.state().surface("F1");
    const auto wrap = faultWrappingIso(*s.currentFrame(), *s.state().fault("F1"), expected);
    ASSERT_TRUE(wrap);
    EXPECT_EQ(s.state().surface("F1")->iso, *wrap);
    EXPECT_GT(*wrap, 1.0); // r/d summed over the lattice: far above the settings' default
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","iso":0.9})"));
    EXPECT_EQ(s.state().surface("F1")->iso, 0.9);
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","iso":"wrap"})"));
    EXPECT_EQ(s.state().surface("F1")->iso, *wrap);
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","iso":2.5})"));
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","kernel":"compact","iso":"wrap"})"));
    expected.kernel = MetaballKernel::Compact;
    EXPECT_EQ(s.state().surface("F1")->iso,
              *faultWrappingIso(*s.currentFrame(), *s.state().fault("F1"), expected));
    expectRefused(s, R"({"op":"surface.set","fault":"F1","iso":"high"})", "(or \"wrap\")");
}

// surface.set without "iso" for a new surface, or one whose kernel changes, under an inverse
// kernel takes the wrapping iso too, as the workbench's Surfaces panel does: the default of 1
// lies outside the whole lattice's r/d^2 field, and its surface would be one ball around it. The
// compact kernel keeps the default, an existing surface its iso-value, and a number is kept.
TEST(Session, ANewInverseSurfaceWithoutAnIsoValueWrapsItsSpheres) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F2","ids":[1,2,3,4,5,6]})"));
    auto wrapOf = [&](const std::string& fault) {
        return *faultWrappingIso(*s.currentFrame(), *s.state().fault(fault),
                                 *s.state().surface(fault));
    };
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","voxel":0.25})")); // inverse-square
    EXPECT_EQ(s.state().surface("F1")->kernel, MetaballKernel::InverseSquare);
    EXPECT_EQ(s.state().surface("F1")->iso, wrapOf("F1"));
    EXPECT_GT(s.state().surface("F1")->iso, 1.0);
    // An existing surface keeps its iso-value when other settings change.
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","iso":3.5})"));
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","voxel":0.3,"opacity":0.5})"));
    EXPECT_EQ(s.state().surface("F1")->iso, 3.5);
    // Another inverse kernel without an iso-value: wrapped for it.
    s.apply(cmd(R"({"op":"surface.set","fault":"F1","kernel":"inverse"})"));
    EXPECT_EQ(s.state().surface("F1")->iso, wrapOf("F1"));
    // The compact kernel keeps the number it has (recorded journals' figures stay).
    s.apply(cmd(R"({"op":"surface.set","fault":"F2","kernel":"compact"})"));
    EXPECT_EQ(s.state().surface("F2")->iso, 1.0);
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(s.state().surface("F2"), nullptr);
    // A number given is kept.
    s.apply(cmd(R"({"op":"surface.set","fault":"F2","iso":0.7})"));
    EXPECT_EQ(s.state().surface("F2")->iso, 0.7);
}

TEST(SessionFile, SaveAndLoadRoundTripWithRelativeDataPaths) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"frame.set","frame":2})"));
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1],"mode":"cut"})"));
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":0.5,"high":9})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[3,1,2],"notes":"a \"quoted\" note"})"));
    s.apply(cmd(R"({"op":"view.add","name":"before","offset":-2})"));
    s.apply(cmd(R"({"op":"color.set","variable":"strain","map":"pastel","range":[0,0.5]})"));
    s.apply(cmd(R"({"op":"layout.set","layout":{"root":{"split":"v","ratio":0.3}}})"));
    const std::string file = dir.file("out/a.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    std::ifstream in(file);
    const Json doc = Json::parse(in);
    EXPECT_EQ(doc["schema"], kSessionSchema);
    EXPECT_EQ(doc["data"]["paths"][0], "../lattice.dump"); // relative to the session file
    SessionState loaded = loadSessionFile(file);
    EXPECT_EQ(loaded, s.state());
    Session restored;
    restored.replaceState(loaded);
    EXPECT_EQ(restored.visibility().visibleCount, s.visibility().visibleCount);
}

TEST(SessionFile, BadFilesAreRefusedWithLocatedMessages) {
    TempDir dir;
    auto refuse = [&](const std::string& content, const std::string& expectedEnd) {
        const std::string p = dir.write("s.faultline.json", content);
        try {
            loadSessionFile(p);
            ADD_FAILURE() << "accepted " << content;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.substr(msg.size() - std::min(msg.size(), expectedEnd.size())),
                      expectedEnd)
                << msg;
        }
    };
    refuse("{\"format\":\"faultline-session\",\"schema\":1,",
           "invalid JSON: syntax error while parsing object key - unexpected end of input; "
           "expected string literal");
    refuse("[1,2]", "not a Faultline session (expected \"format\": \"faultline-session\")");
    // Found by fuzz_session_file: a "format" that is no string escaped as a library exception.
    refuse(R"({"'Ap":"ap","format":{}})",
           "not a Faultline session (expected \"format\": \"faultline-session\")");
    refuse(
        R"({"format":"faultline-session","schema":99})",
        "session schema 99 is newer than this Faultline understands (1): please update Faultline");
    refuse(R"({"format":"faultline-session","schema":1,"faults":[{"name":"F","color":[2,0,0]}]})",
           "faults[0].color: components must lie in [0, 1]");
    refuse(
        R"({"format":"faultline-session","schema":1,"boxes":[{"name":"a","min":[0,0,0],"max":[1,1]}]})",
        "boxes[0].max: must be an array of 3 numbers");
    refuse(
        R"({"format":"faultline-session","schema":1,"views":[{"name":"main","camera":{"fov_y":0}}]})",
        "views[0].camera.fov_y: must lie in (0, 180)");
    // The same rules as threshold.add (one codec): a file cannot hold what a command refuses.
    refuse(
        R"({"format":"faultline-session","schema":1,"thresholds":[{"variable":"s","low":2,"high":1}]})",
        "thresholds[0].low: must not exceed high");
    refuse(R"({"format":"faultline-session","schema":1,"faults":[{"name":"*visible"}]})",
           "faults[0].name: \"*visible\" names the visible spheres' surface, not a fault");
    refuse(
        R"({"format":"faultline-session","schema":1,"surfaces":[{"fault":"*visible","range":[2,1]}]})",
        "surfaces[0].range: must be [low, high] with low < high, or null");
    refuse(std::string(100, '[') + std::string(100, ']'), "JSON nested deeper than 64 levels");
    // Found by fuzz_journal: a number beyond double escaped as a library exception.
    refuse(R"({"format":"faultline-session","schema":1e999})",
           "invalid JSON: number overflow parsing '1e999'");
}

TEST(SessionFile, MissingDataLeavesTheSessionUntouched) {
    TempDir dir;
    Session s;
    s.apply(cmd(R"({"op":"box.add","name":"keep","min":[0,0,0],"max":[1,1,1]})"));
    const SessionState before = s.state();
    SessionState other;
    other.dataPaths = {dir.file("moved-away.dump")};
    EXPECT_THROW(s.replaceState(other), InputError);
    EXPECT_EQ(s.state(), before);
}

TEST(Journal, LinesAreCheckedBeforeAnythingRuns) {
    Session s;
    auto errorOf = [&](const std::string& text) {
        try {
            parseJournal(text, "j.jsonl", s);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(errorOf("// comment\n\n{\"op\":\"frame.set\",\"frame\":1}\n{\"op\":\"teleport\"}\n"),
              "j.jsonl:4: unknown op \"teleport\"");
    EXPECT_EQ(errorOf("{\"op\":\"undo\"}\n{\"expect\":\"vibes\"}\n"),
              "j.jsonl:2: unknown expectation \"vibes\"");
    EXPECT_EQ(errorOf("{\"op\":\"undo\"\n"), "j.jsonl:1: invalid JSON: syntax error while parsing "
                                             "object - unexpected end of input; expected '}'");
    EXPECT_EQ(errorOf("{\"op\":\"undo\",\"expect\":\"frame\"}\n"),
              "j.jsonl:1: a line needs exactly one of \"op\" or \"expect\"");
    EXPECT_EQ(errorOf("[1]\n"), "j.jsonl:1: expected a JSON object with \"op\" or \"expect\"");
    EXPECT_EQ(
        parseJournal("{\"op\":\"undo\"}\r\n  // x\n{\"expect\":\"frame\",\"equals\":0}", "j", s)
            .size(),
        2u);
}

TEST(Journal, ReplayReportsEachFailingExpectation) {
    TempDir dir;
    writeLattice(dir);
    const std::string journal = dir.write(
        "j.jsonl", "{\"op\":\"data.open\",\"paths\":[\"lattice.dump\"]}\n"
                   "{\"op\":\"threshold.add\",\"variable\":\"layer\",\"low\":2,\"high\":3}\n"
                   "{\"expect\":\"visible_count\",\"equals\":32}\n"
                   "{\"expect\":\"visible_count\",\"equals\":31}\n"
                   "{\"expect\":\"histogram\",\"variable\":\"layer\",\"of\":\"visible\",\"bins\":4,"
                   "\"range\":[0,4],\"counts\":[0,0,16,16]}\n"
                   "{\"op\":\"fault.create\",\"name\":\"F1\",\"from\":\"visible\"}\n"
                   "{\"expect\":\"fault_size\",\"name\":\"F1\",\"equals\":32}\n"
                   "{\"op\":\"session.save\",\"path\":\"out/s.faultline.json\"}\n"
                   "{\"expect\":\"file_exists\",\"path\":\"out/s.faultline.json\"}\n"
                   "{\"expect\":\"file_exists\",\"path\":\"out/nothing.png\"}\n");
    Session s;
    ReplayReport report = replayJournal(journal, {}, s);
    EXPECT_EQ(report.commands, 4u);
    EXPECT_EQ(report.expectations, 6u);
    ASSERT_EQ(report.failures.size(), 2u);
    EXPECT_EQ(report.failures[0].line, 4u);
    EXPECT_EQ(report.failures[0].message, "expect visible_count: expected 31, actual 32");
    EXPECT_EQ(report.failures[1].line, 10u);
    EXPECT_FALSE(report.stopped);
}

TEST(Journal, DataOverrideRetargetsTheAnalysis) {
    TempDir dir;
    writeLattice(dir);
    const std::string other =
        dir.write("other.csv", "id,x,y,z,layer\n1,0,0,0,2\n2,1,0,0,3\n3,2,0,0,0\n");
    const std::string journal = dir.write(
        "j.jsonl", "{\"op\":\"data.open\",\"paths\":[\"lattice.dump\"]}\n"
                   "{\"op\":\"threshold.add\",\"variable\":\"layer\",\"low\":2,\"high\":3}\n"
                   "{\"expect\":\"visible_count\",\"equals\":2}\n");
    Session s;
    ReplayOptions options;
    options.data = {other};
    EXPECT_TRUE(replayJournal(journal, options, s).ok());
}

TEST(Journal, FailingCommandStopsTheReplay) {
    TempDir dir;
    const std::string journal = dir.write(
        "j.jsonl", "{\"op\":\"frame.set\",\"frame\":1}\n{\"expect\":\"frame\",\"equals\":1}\n");
    Session s;
    ReplayReport report = replayJournal(journal, {}, s);
    EXPECT_TRUE(report.stopped);
    ASSERT_EQ(report.failures.size(), 1u);
    EXPECT_EQ(report.failures[0].message, "frame.set: no data is open");
}

TEST(Session, CandidatesAndSplitUndoExactly) {
    TempDir dir;
    Session s;
    openTwoWalls(s, dir);
    const SessionState before = s.state();
    s.apply(cmd(R"({"op":"fault.candidates","link":1.1,"min_size":5,"prefix":"K"})"));
    ASSERT_EQ(s.state().faults.size(), 2u);
    EXPECT_EQ(s.state().fault("K1")->ids.size(), 16u);
    EXPECT_EQ(s.state().fault("K1")->ids.front(), 1); // equal sizes: the smaller id first
    s.apply(cmd(R"({"op":"fault.merge","names":["K1","K2"],"into":"K"})"));
    const SessionState merged = s.state();
    s.apply(cmd(R"({"op":"fault.split","name":"K"})"));
    EXPECT_EQ(s.state().fault("K.1")->ids.size(), 16u);
    EXPECT_EQ(s.state().fault("K.2")->ids.size(), 16u);
    EXPECT_FALSE(s.state().fault("K"));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(dump(s.state()), dump(merged));
    s.apply(cmd(R"({"op":"undo"})"));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(dump(s.state()), dump(before));
    // None found: no fault, an undo step of its own (so an undo after it undoes nothing else),
    // and a note saying why (issue 37: a loop over frames stopped at the first frame without).
    const SessionState none = s.state();
    s.apply(cmd(R"({"op":"fault.candidates","min_size":100})"));
    EXPECT_EQ(dump(s.state()), dump(none));
    EXPECT_NE(s.lastNote().find("no faults made: no group of at least 100 visible spheres"),
              std::string::npos)
        << s.lastNote();
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(dump(s.state()), dump(none));
    s.apply(cmd(R"({"op":"fault.create","name":"K1","ids":[1]})"));
    EXPECT_THROW(s.apply(cmd(R"({"op":"fault.candidates","min_size":5,"prefix":"K"})")),
                 CommandError);
    EXPECT_THROW(s.apply(cmd(R"({"op":"fault.split","name":"K1"})")), CommandError); // one piece
}

// Issue 27: a split keeps the fault's colour on its largest piece and its surface settings on
// every piece (an inverse kernel's iso scaled to each piece's wrapping iso), and makes no fault of
// a piece under min_size: its spheres stay with the largest piece.
TEST(Session, SplitKeepsColourAndSurfaceSettingsAndDropsTinyPieces) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    // id = 1 + x + 4 y + 16 z: the west wall (16), a row of the east wall at z = 0 (4), and two
    // spheres of it at z = 3 (2): three connected pieces.
    std::vector<std::int64_t> ids;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y)
            ids.push_back(1 + 4 * y + 16 * z);
    for (int y = 0; y < 4; ++y)
        ids.push_back(4 + 4 * y);
    ids.push_back(52), ids.push_back(56);
    s.apply({{"op", "fault.create"}, {"name", "K"}, {"ids", ids}, {"color", {1.0, 0.0, 0.0}}});
    s.apply(cmd(R"({"op":"surface.set","fault":"K","kernel":"inverse","iso":2.0,"opacity":0.5})"));
    const SessionState before = s.state();
    const Fault whole = *s.state().fault("K");
    const SurfaceSettings settings = *s.state().surface("K");
    const double wrapWhole = *faultWrappingIso(*s.currentFrame(), whole, settings);
    s.apply(cmd(R"({"op":"fault.split","name":"K","method":"connected","min_size":3})"));
    ASSERT_TRUE(s.state().fault("K.1"));
    ASSERT_TRUE(s.state().fault("K.2"));
    EXPECT_FALSE(s.state().fault("K.3")); // the two-sphere piece
    EXPECT_EQ(s.state().fault("K.1")->ids.size(), 18u);
    EXPECT_EQ(s.state().fault("K.2")->ids.size(), 4u);
    EXPECT_EQ(s.state().fault("K.1")->color, whole.color);
    EXPECT_NE(s.state().fault("K.2")->color, whole.color);
    for (const char* piece : {"K.1", "K.2"}) {
        SCOPED_TRACE(piece);
        const SurfaceSettings* st = s.state().surface(piece);
        ASSERT_TRUE(st);
        EXPECT_EQ(st->kernel, MetaballKernel::Inverse);
        EXPECT_DOUBLE_EQ(st->opacity, 0.5);
        const double wrap = *faultWrappingIso(*s.currentFrame(), *s.state().fault(piece), *st);
        EXPECT_NEAR(st->iso, 2.0 * wrap / wrapWhole, 0.01 * st->iso);
    }
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(dump(s.state()), dump(before));
    // A compact kernel's iso is absolute: every piece keeps it.
    s.apply(cmd(R"({"op":"surface.set","fault":"K","kernel":"compact","iso":0.7})"));
    s.apply(cmd(R"({"op":"fault.split","name":"K","method":"connected","min_size":3})"));
    EXPECT_DOUBLE_EQ(s.state().surface("K.2")->iso, 0.7);
    // Under the default min_size (10) only the wall is a piece: nothing to split.
    s.apply(cmd(R"({"op":"undo"})"));
    expectRefused(s, R"({"op":"fault.split","name":"K","method":"connected"})",
                  "of at least 10 spheres");
}

TEST(SessionFile, LargeFaultsArePackedAndRoundTrip) {
    TempDir dir;
    SessionState st;
    Fault big;
    big.name = "big";
    for (std::int64_t id = 0; id < 20000; id += 3)
        big.ids.push_back(id - 100);
    st.faults.push_back(big);
    const std::string file = dir.file("s.faultline.json");
    saveSessionFile(st, file);
    std::ifstream in(file);
    const Json doc = Json::parse(in);
    EXPECT_TRUE(doc["faults"][0].contains("ids_packed"));
    EXPECT_FALSE(doc["faults"][0].contains("ids"));
    EXPECT_EQ(loadSessionFile(file), st);
}

TEST(Session, PreviewRunsTheOpsOnACopyAndChangesNothing) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":0.1,"high":1})"));
    const std::string before = dump(s.state());
    const std::uint64_t version = s.version();
    const std::size_t journal = s.journal().size(), undo = s.undoDepth();
    const std::vector<Json> edits = {
        cmd(R"({"op":"box.set","name":"a","max":[2,2,2]})"),
        cmd(R"({"op":"threshold.set","variable":"strain","low":0.5,"high":0.2})"), // refused
        cmd(R"({"op":"threshold.set","variable":"strain","low":0.3})"),
        cmd(R"({"op":"camera.set","view":"main","azimuth":40})"),
        cmd(R"({"op":"fault.create","name":"F","ids":[1]})"),    // not a preview op
        cmd(R"({"op":"box.set","name":"nope","max":[2,2,2]})")}; // refused
    const Session::Preview p = s.preview(edits);
    EXPECT_EQ(p.applied, 3u);
    ASSERT_EQ(p.boxes.size(), 1u);
    EXPECT_EQ(p.boxes[0].max, (std::array<double, 3>{2, 2, 2}));
    ASSERT_EQ(p.thresholds.size(), 1u);
    EXPECT_EQ(p.thresholds[0].low, 0.3); // the refused low > high changed nothing
    EXPECT_EQ(p.thresholds[0].high, 1.0);
    ASSERT_FALSE(p.views.empty());
    EXPECT_EQ(p.views[0].camera.azimuth, 40.0);
    EXPECT_EQ(dump(s.state()), before);
    EXPECT_EQ(s.version(), version);
    EXPECT_EQ(s.journal().size(), journal);
    EXPECT_EQ(s.undoDepth(), undo);
    EXPECT_FALSE(s.state().fault("F"));
}

// The demo's starting view is one batch of five commands; its undo step says what it is
// ("Undone: the demo's starting view"), not "5 changes", through undo and redo.
TEST(Session, AStepCanBeNamedInWordsItsCommandCannotGive) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"batch","commands":[{"op":"frame.set","frame":2},
        {"op":"threshold.add","variable":"strain","low":1,"high":1e30}]})"));
    EXPECT_EQ(s.undoLabel(), "add a strain threshold"); // moving in time is no change
    s.relabelLastUndo("the demo's starting view");
    EXPECT_EQ(s.undoLabel(), "the demo's starting view");
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(s.redoLabel(), "the demo's starting view");
    ASSERT_TRUE(s.redo());
    EXPECT_EQ(s.undoLabel(), "the demo's starting view");
}

// Issue 41, item 3: a sphere belongs to at most one fault. Putting it into another moves it,
// says so, and undoes exactly.
TEST(Session, ASphereBelongsToOneFault) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    s.apply(cmd(R"({"op":"fault.create","name":"C2","ids":[3,4,5]})"));
    const SessionState before = s.state();
    s.apply(cmd(R"({"op":"fault.create","name":"F1","ids":[1,2,3]})"));
    EXPECT_EQ(s.lastNote(), "moved 1 from C2 to F1");
    EXPECT_EQ(s.state().fault("C2")->ids, (std::vector<std::int64_t>{4, 5}));
    s.apply(cmd(R"({"op":"fault.add","name":"F1","ids":[4,5,9]})"));
    EXPECT_EQ(s.lastNote(), "moved 2 from C2 to F1");
    EXPECT_TRUE(s.state().fault("C2")->ids.empty());
    EXPECT_EQ(s.state().fault("F1")->ids, (std::vector<std::int64_t>{1, 2, 3, 4, 5, 9}));
    // Undo and redo say that spheres moved (walkthrough: "Redo: add 1 sphere to C1" for a move).
    EXPECT_EQ(s.undoLabel(), "add 3 spheres to F1 (moved 2 from C2)");
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(s.redoLabel(), "add 3 spheres to F1 (moved 2 from C2)");
    EXPECT_EQ(s.state().fault("C2")->ids, (std::vector<std::int64_t>{4, 5}));
    s.apply(cmd(R"({"op":"undo"})"));
    EXPECT_EQ(s.state(), before);
    s.apply(cmd(R"({"op":"redo"})"));
    s.apply(cmd(R"({"op":"redo"})"));
    EXPECT_TRUE(s.state().fault("C2")->ids.empty());
    // Every sphere in one fault at most.
    std::set<std::int64_t> seen;
    for (const auto& f : s.state().faults)
        for (auto id : f.ids)
            EXPECT_TRUE(seen.insert(id).second) << id << " in two faults";
}

// Issue 41, item 11: a fault's surface is built from what of it has formed in the frame shown
// (its members passing the thresholds), so it is not drawn before any of its spheres passed.
TEST(Session, AFaultsSurfaceIsWhatOfItHasFormedInTheFrame) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    // x = 2 and x = 3 (32 spheres); strain = x/3 + frame.
    s.apply(cmd(R"({"op":"box.add","name":"east","min":[2,0,0],"max":[3,3,3]})"));
    s.apply(cmd(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    s.apply(cmd(R"({"op":"box.remove","name":"east"})"));
    const Fault whole = *s.state().fault("F1");
    ASSERT_EQ(whole.ids.size(), 32u);
    s.apply(cmd(R"({"op":"threshold.add","variable":"strain","low":2.8,"high":1e30})"));
    auto frame0 = s.currentFrame();
    EXPECT_TRUE(faultAsFormed(*frame0, whole, s.state().thresholds).ids.empty());
    expectRefused(s, R"({"op":"surface.build","fault":"F1"})",
                  "none of F1's 32 spheres passes the thresholds in frame 0: it has not formed");
    s.apply(cmd(R"({"op":"frame.set","frame":2})")); // x = 3 passes (strain 3), x = 2 not (2.67)
    const Fault formed = faultAsFormed(*s.currentFrame(), whole, s.state().thresholds);
    EXPECT_EQ(formed.ids.size(), 16u);
    EXPECT_EQ(formed.name, "F1");
    EXPECT_EQ(formed.color, whole.color);
    s.apply(cmd(R"({"op":"surface.build","fault":"F1","voxel":0.25})"));
    // No threshold enabled: the whole fault, as before.
    s.apply(cmd(R"({"op":"threshold.set","variable":"strain","enabled":false})"));
    EXPECT_EQ(faultAsFormed(*s.currentFrame(), whole, s.state().thresholds).ids.size(), 32u);
}

// Issue 41, item 11: distributed damage accepted as candidates says so in the fault's notes.
TEST(Session, DiffuseCandidatesSayWhatTheyAre) {
    TempDir dir;
    Session s;
    openTwoWalls(s, dir); // two thin walls: sheets, upright
    s.apply(cmd(R"({"op":"fault.candidates","min_size":10})"));
    ASSERT_EQ(s.state().faults.size(), 2u);
    EXPECT_EQ(s.state().faults[0].notes, "");
    EXPECT_EQ(s.state().faults[1].notes, "");
    s.apply(cmd(R"({"op":"undo"})"));
    // Three layers of the 4x4x4 block: a blob, nearly as thick as it is wide.
    s.apply(cmd(R"({"op":"box.remove","name":"west"})"));
    s.apply(cmd(R"({"op":"box.set","name":"east","min":[0,0,0],"max":[3,3,2]})"));
    s.apply(cmd(R"({"op":"fault.candidates","min_size":10,"method":"connected"})"));
    ASSERT_EQ(s.state().faults.size(), 1u);
    EXPECT_NE(s.state().faults[0].notes.find("diffuse"), std::string::npos)
        << s.state().faults[0].notes;
    const CandidateShape sheet =
        candidateShape(*s.currentFrame(), std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10,
                                                                    11, 12, 13, 14, 15, 16});
    EXPECT_TRUE(sheet.valid);
    EXPECT_FALSE(sheet.diffuse); // the z = 0 layer
    EXPECT_NEAR(sheet.dip, 0.0, 1e-6);
    // Flat (issue 37): flagged, and said so by the notes with the journal's op too.
    EXPECT_TRUE(sheet.subHorizontal);
    EXPECT_EQ(shapeNote(sheet).rfind("sub-horizontal: dips 0.0 degrees", 0), 0u)
        << shapeNote(sheet);
    s.apply(cmd(R"({"op":"undo"})"));
    s.apply(cmd(R"({"op":"box.set","name":"east","min":[0,0,0],"max":[3,3,0]})"));
    s.apply(cmd(R"({"op":"fault.candidates","min_size":10})"));
    ASSERT_EQ(s.state().faults.size(), 1u);
    EXPECT_EQ(s.state().faults[0].notes, shapeNote(sheet));
}

// Issue 39: one cache of visible spheres keyed by what they depend on. The same selection in the
// same frame is one result; a camera move or a rename of nothing visible keeps it; a box, a
// threshold, the fault filter or a fault's members make another.
TEST(Session, VisibilityIsOneResultPerFrameAndSelection) {
    TempDir dir;
    Session s;
    s.apply({{"op", "data.open"}, {"paths", {writeLattice(dir)}}});
    const auto frame = s.currentFrame();
    const auto first = s.visibilityOf(frame, s.state().boxes, s.state().thresholds);
    EXPECT_EQ(&s.visibility(), first.result.get()); // the session's own is the same result
    s.apply(cmd(R"({"op":"camera.set","view":"main","azimuth":40})"));
    EXPECT_EQ(&s.visibility(), first.result.get()) << "a camera move computed it again";
    s.apply(cmd(R"({"op":"box.add","name":"low","min":[0,0,0],"max":[3,3,1]})"));
    EXPECT_EQ(s.visibility().visibleCount, 32u);
    const auto boxed = s.visibilityOf(frame, s.state().boxes, s.state().thresholds);
    EXPECT_NE(boxed.key, first.key);
    s.undo(); // back to no box: the first result again, not worked out anew
    EXPECT_EQ(&s.visibility(), first.result.get());
    s.apply(cmd(R"({"op":"fault.create","name":"F","ids":[1,2,3]})"));
    s.apply(cmd(R"({"op":"fault.filter","mode":"only","fault":"F"})"));
    EXPECT_EQ(s.visibility().visibleCount, 3u);
    s.apply(cmd(R"({"op":"fault.add","name":"F","ids":[4]})")); // members change: another
    EXPECT_EQ(s.visibility().visibleCount, 4u);
    // A preview's selection (a box being dragged) is another key, the session's stays.
    std::vector<CuttingBox> dragged = s.state().boxes;
    dragged.push_back({"drag", {0, 0, 0}, {0, 0, 0}, BoxMode::Keep, true});
    const auto preview = s.visibilityOf(frame, dragged, s.state().thresholds);
    EXPECT_EQ(preview.result->visibleCount, 1u); // sphere 1 at the origin
    EXPECT_EQ(s.visibility().visibleCount, 4u);
}
