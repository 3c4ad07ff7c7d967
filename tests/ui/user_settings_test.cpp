// ui::UserSettings (issue 39: out of the Workbench): recent files and the frame memory budget
// kept between runs; a damaged file loses only what it held.
#include "../core/test_files.hpp"
#include "ui/workbench/user_settings.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

using faultline::test::TempDir;
using faultline::ui::UserSettings;

TEST(UserSettings, RecentFilesComeBackNewestFirstTenAtMost) {
    TempDir dir;
    {
        UserSettings s(dir.path());
        for (int k = 0; k < 12; ++k)
            s.addRecent("/data/run" + std::to_string(k) + ".dump");
        s.addRecent("/data/run5.dump"); // again: moves to the front, not twice
        s.addRecent("");
        s.setFrameBudget(std::size_t(512) << 20);
    }
    const UserSettings again(dir.path());
    ASSERT_EQ(again.recent().size(), 10u);
    EXPECT_EQ(again.recent()[0], "/data/run5.dump");
    EXPECT_EQ(again.recent()[1], "/data/run11.dump");
    EXPECT_EQ(std::count(again.recent().begin(), again.recent().end(), "/data/run5.dump"), 1);
    EXPECT_EQ(again.frameBudget(), std::size_t(512) << 20);
}

TEST(UserSettings, ADamagedFileOrNoFolderKeepsNothing) {
    TempDir dir;
    std::ofstream(dir.file("settings.json")) << "{\"recent\": [\"/a\", 3, ";
    const UserSettings damaged(dir.path());
    EXPECT_TRUE(damaged.recent().empty());
    EXPECT_EQ(damaged.frameBudget(), 0u);
    UserSettings none("");
    none.addRecent("/a");
    EXPECT_EQ(none.recent().size(), 1u); // kept for this run, written nowhere
}
