// core::JournalRecorder (issue 39: the journal out of Session): lines recorded behind an action
// the caller runs in the background wait for it, in the order they were asked for.
#include "core/session/journal_recorder.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;

TEST(JournalRecorder, LinesBehindAnOpenActionWaitForIt) {
    JournalRecorder j;
    std::vector<Json> written, held;
    j.setSinks([&](const Json& c) { written.push_back(c); },
               [&](const Json& c) { held.push_back(c); });
    j.record({{"op", "a"}});
    const auto exportPlace = j.reserve();
    const auto otherPlace = j.reserve();
    j.record({{"op", "b"}}); // behind both places: held, not yet in its place
    EXPECT_EQ(j.pending(), 2u);
    EXPECT_EQ(held.size(), 1u);
    EXPECT_EQ(j.lines().size(), 1u);
    j.settle(otherPlace, {{"op", "other"}}); // the older place still open: nothing moves
    EXPECT_EQ(j.lines().size(), 1u);
    j.settle(exportPlace, {{"op", "export"}});
    ASSERT_EQ(j.lines().size(), 4u);
    EXPECT_EQ(j.lines()[1]["op"], "export"); // where it was asked for
    EXPECT_EQ(j.lines()[2]["op"], "other");
    EXPECT_EQ(j.lines()[3]["op"], "b");
    EXPECT_EQ(written, j.lines());
    EXPECT_EQ(j.pending(), 0u);
}

TEST(JournalRecorder, ADroppedActionRecordsNothing) {
    JournalRecorder j;
    const auto place = j.reserve();
    j.record({{"op", "b"}});
    j.drop(place);
    ASSERT_EQ(j.lines().size(), 1u);
    EXPECT_EQ(j.lines()[0]["op"], "b");
    j.reserve();
    j.record({{"op", "c"}});
    j.dropPending(); // shutdown: the waiting lines are written
    EXPECT_EQ(j.lines().size(), 2u);
}
