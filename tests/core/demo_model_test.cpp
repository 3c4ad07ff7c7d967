#include "core/synth/demo_model.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace faultline::core;

namespace {
struct ScopedEnv {
    ScopedEnv(const char* name, const char* value) : m_name(name) {
        if (const char* old = std::getenv(name))
            m_old = old;
        if (value)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv() {
        if (m_old)
            ::setenv(m_name, m_old->c_str(), 1);
        else
            ::unsetenv(m_name);
    }
    const char* m_name;
    std::optional<std::string> m_old;
};
} // namespace

TEST(DemoModel, FolderFollowsXdgThenHome) {
    {
        ScopedEnv xdg("XDG_DATA_HOME", "/data/me");
        EXPECT_EQ(demoModelFolder(), "/data/me/faultline/demo");
    }
    {
        ScopedEnv xdg("XDG_DATA_HOME", nullptr);
        ScopedEnv home("HOME", "/home/me");
        EXPECT_EQ(demoModelFolder(), "/home/me/.local/share/faultline/demo");
    }
    {
        ScopedEnv xdg("XDG_DATA_HOME", "relative/is/ignored");
        ScopedEnv home("HOME", "/home/me");
        EXPECT_EQ(demoModelFolder(), "/home/me/.local/share/faultline/demo");
    }
    {
        ScopedEnv xdg("XDG_DATA_HOME", nullptr);
        ScopedEnv home("HOME", nullptr);
        EXPECT_THROW(demoModelFolder(), std::runtime_error);
    }
}

TEST(DemoModel, ACompleteDemoIsReusedAndAPartialOneIsNot) {
    const auto root =
        std::filesystem::temp_directory_path() /
        ("faultline_demo_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    std::filesystem::remove_all(root);
    ScopedEnv xdg("XDG_DATA_HOME", root.c_str());
    const auto folder = std::filesystem::path(demoModelFolder());
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "block-v2.lammpstrj.gz") << "x";
    EXPECT_FALSE(existingDemoModel()) << "no info file: an interrupted demo";
    std::ofstream(folder / "block-v2.json") << "{}";
    ASSERT_TRUE(existingDemoModel());
    EXPECT_EQ(*existingDemoModel(), (folder / "block-v2.lammpstrj.gz").string());
    // Reused without generating anything (the progress callback would cancel).
    EXPECT_EQ(ensureDemoModel([](double) { return false; }), *existingDemoModel());
    std::filesystem::remove_all(root);
}

TEST(DemoModel, CancelledGenerationLeavesNothingBehind) {
    const auto root = std::filesystem::temp_directory_path() /
                      ("faultline_demo_cancel_" +
                       std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    std::filesystem::remove_all(root);
    ScopedEnv xdg("XDG_DATA_HOME", root.c_str());
    EXPECT_THROW(ensureDemoModel([](double) { return false; }), GenerationCancelled);
    EXPECT_FALSE(existingDemoModel());
    // Only the parent folder remains, empty.
    const auto parent = std::filesystem::path(demoModelFolder()).parent_path();
    EXPECT_TRUE(std::filesystem::is_empty(parent));
    std::filesystem::remove_all(root);
}
