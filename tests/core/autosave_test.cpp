#include "core/session/autosave.hpp"
#include "core/session/session_json.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;
using faultline::test::TempDir;
using namespace std::chrono_literals;

TEST(Autosave, SavesEveryIntervalOnlyWhenChanged) {
    TempDir dir;
    Autosave autosave(dir.file("state"));
    Session s;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_FALSE(autosave.tick(s, t0));
    s.apply(Json::parse(R"({"op":"box.add","name":"a","min":[0,0,0],"max":[1,1,1]})"));
    EXPECT_FALSE(autosave.tick(s, t0 + 59s));
    EXPECT_TRUE(autosave.tick(s, t0 + 61s));
    EXPECT_FALSE(autosave.tick(s, t0 + 200s)); // unchanged since
    EXPECT_EQ(loadSessionFile(autosave.sessionPath()).boxes.size(), 1u);
}

TEST(Autosave, CrashLeavesARecoveryACleanExitDoesNot) {
    TempDir dir;
    Session s;
    s.apply(Json::parse(R"({"op":"fault.create","name":"F1","ids":[1,2]})"));
    {
        Autosave autosave(dir.file("state"));
        ASSERT_TRUE(autosave.saveNow(s, false)); // then the process "crashes"
    }
    Autosave next(dir.file("state"));
    auto pending = next.pending();
    ASSERT_TRUE(pending);
    EXPECT_EQ(loadSessionFile(pending->sessionPath).faults.size(), 1u);
    next.discard();
    EXPECT_FALSE(next.pending());
    ASSERT_TRUE(next.saveNow(s, true));
    EXPECT_FALSE(Autosave(dir.file("state")).pending());
}

TEST(Autosave, UnwritableFolderIsReportedNotThrown) {
    TempDir dir;
    dir.write("blocker", "a file where the folder should be");
    Autosave autosave(dir.file("blocker/state"));
    Session s;
    EXPECT_FALSE(autosave.saveNow(s, false));
    EXPECT_FALSE(autosave.lastError().empty());
}
