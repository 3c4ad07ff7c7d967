// Never lose work: the session's unsaved state, the question before quitting or opening over it,
// and a process killed with unsaved changes offering them back at the next start.
#include "../core/test_files.hpp"
#include "headless_ui.hpp"
#include "panel_fixture.hpp"

#include "core/session/autosave.hpp"
#include "core/session/session_json.hpp"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

using namespace faultline;
using namespace faultline::test;
using core::Json;

namespace {

class UnsavedWork : public PanelTest {
  protected:
    // The killed child of the last test shares its parent's state folder.
    std::string stateDir() override {
        const char* parent = std::getenv("FAULTLINE_UNSAVED_DIR");
        return parent ? std::string(parent) + "/state" : dir.file("state");
    }
    void addBox(const char* name) {
        session.apply({{"op", "box.add"}, {"name", name}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}});
    }
};

} // namespace

TEST(SessionModified, ChangesSinceTheLastSaveOrOpen) {
    TempDir dir;
    core::Session s;
    EXPECT_FALSE(s.modified());
    s.apply(Json::parse(R"({"op":"box.add","name":"b","min":[0,0,0],"max":[1,1,1]})"));
    EXPECT_TRUE(s.modified());
    const std::string file = dir.file("a.faultline.json");
    s.apply({{"op", "session.save"}, {"path", file}});
    EXPECT_FALSE(s.modified());
    s.apply({{"op", "export.csv"}, {"what", "faults"}, {"path", dir.file("f.csv")}});
    EXPECT_FALSE(s.modified()) << "an export changes nothing";
    s.apply(Json::parse(R"({"op":"undo"})"));
    EXPECT_TRUE(s.modified());
    s.apply({{"op", "session.open"}, {"path", file}});
    EXPECT_FALSE(s.modified()) << "an opened session is what is on disk";
    s.apply(Json::parse(R"({"op":"box.set","name":"b","enabled":false})"));
    EXPECT_TRUE(s.modified());
}

TEST_F(UnsavedWork, OpeningDataIntoAFreshSessionLeavesNothingToSave) {
    openLattice();
    EXPECT_FALSE(wb().hasUnsavedChanges());
    EXPECT_EQ(wb().windowTitle(), "Faultline - unsaved session");
    addBox("b");
    headless.frames(wb(), 1);
    EXPECT_TRUE(wb().hasUnsavedChanges());
    EXPECT_EQ(wb().windowTitle(), "Faultline - unsaved session *");
}

TEST_F(UnsavedWork, QuitAsksAndCancelKeepsTheWorkbench) {
    openLattice();
    addBox("b");
    wb().requestQuit();
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().unsavedPromptOpen());
    EXPECT_FALSE(wb().quitRequested());
    headless.click(wb(), "unsaved.cancel");
    headless.frames(wb(), 1);
    EXPECT_FALSE(wb().unsavedPromptOpen());
    EXPECT_FALSE(wb().quitRequested());
    // Ctrl+Q asks the same; Discard quits.
    headless.key(wb(), GLFW_KEY_Q, true);
    headless.frames(wb(), 1);
    ASSERT_TRUE(wb().unsavedPromptOpen());
    headless.click(wb(), "unsaved.discard");
    headless.frames(wb(), 1);
    EXPECT_TRUE(wb().quitRequested());
}

TEST_F(UnsavedWork, SaveFromTheQuestionWritesTheSessionThenQuits) {
    openLattice();
    const std::string file = dir.file("kept.faultline.json");
    wb().saveSessionAs(file);
    headless.frames(wb(), 2);
    ASSERT_FALSE(wb().hasUnsavedChanges()) << wb().lastMessage();
    addBox("after the save");
    wb().requestQuit();
    headless.frames(wb(), 2);
    headless.click(wb(), "unsaved.save");
    headless.frames(wb(), 3);
    EXPECT_TRUE(wb().quitRequested()) << wb().lastMessage();
    EXPECT_NE(core::loadSessionFile(file).box("after the save"), nullptr);
    EXPECT_FALSE(wb().hasUnsavedChanges());
}

// Issue 41, item 1: open a saved session, Ctrl+Z, Ctrl+S. Undo used to revert the open (an
// empty workbench still bound to the file) and the save then wrote the emptiness over it.
TEST_F(UnsavedWork, UndoAfterOpeningASessionCannotEmptyItsFile) {
    openLattice();
    session.apply(core::Json::parse(R"({"op":"fault.create","name":"F1","ids":[1,2,3,4,5]})"));
    addBox("b");
    const std::string file = dir.file("analysis.faultline.json");
    wb().saveSessionAs(file);
    headless.frames(wb(), 2);
    const auto sizeBefore = std::filesystem::file_size(file);

    // A fresh workbench opens the file, as after a restart.
    const auto again = reopen(file);
    ui::Workbench& reopened = again->wb;
    const core::Session& other = again->session;
    ASSERT_NE(other.state().fault("F1"), nullptr) << reopened.lastMessage();
    headless.key(reopened, GLFW_KEY_Z, true); // Ctrl+Z: nothing to undo, the open stays
    headless.frames(reopened, 2);
    EXPECT_NE(other.state().fault("F1"), nullptr);
    EXPECT_FALSE(other.state().dataPaths.empty());
    headless.key(reopened, GLFW_KEY_S, true); // Ctrl+S
    headless.frames(reopened, 3);
    EXPECT_FALSE(reopened.overwritePromptOpen());
    const core::SessionState onDisk = core::loadSessionFile(file);
    ASSERT_NE(onDisk.fault("F1"), nullptr);
    EXPECT_EQ(onDisk.fault("F1")->ids.size(), 5u);
    EXPECT_NE(onDisk.box("b"), nullptr);
    EXPECT_GE(std::filesystem::file_size(file) + 64, sizeBefore);

    // Closing the data and saving would drop the data and the file's fault: asked first, and
    // Cancel writes nothing.
    reopened.emit({{"op", "data.close"}}, {});
    reopened.emit({{"op", "fault.delete"}, {"name", "F1"}}, {});
    headless.frames(reopened, 2);
    headless.key(reopened, GLFW_KEY_S, true);
    headless.frames(reopened, 2);
    ASSERT_TRUE(reopened.overwritePromptOpen());
    EXPECT_EQ(reopened.overwriteLoss(),
              (std::vector<std::string>{"the data (lattice.dump)", "fault F1 (5 spheres)"}));
    headless.click(reopened, "overwrite.cancel");
    headless.frames(reopened, 2);
    EXPECT_FALSE(reopened.overwritePromptOpen());
    EXPECT_NE(core::loadSessionFile(file).fault("F1"), nullptr);
    // Replace, once asked, writes it.
    headless.key(reopened, GLFW_KEY_S, true);
    headless.frames(reopened, 2);
    headless.click(reopened, "overwrite.replace");
    headless.frames(reopened, 3);
    EXPECT_EQ(core::loadSessionFile(file).fault("F1"), nullptr);
}

// Open Recent of the session's own file, with unsaved changes: the question must not offer to
// save over the file being opened.
TEST_F(UnsavedWork, ReopeningTheSessionsOwnFileOffersNoSaveOverIt) {
    openLattice();
    const std::string file = dir.file("own.faultline.json");
    wb().saveSessionAs(file);
    headless.frames(wb(), 2);
    addBox("unsaved");
    headless.frames(wb(), 1);
    wb().guardUnsaved(
        "Open own.faultline.json", [] {}, file);
    headless.frames(wb(), 2);
    ASSERT_TRUE(wb().unsavedPromptOpen());
    EXPECT_FALSE(wb().unsavedPromptOffersSave());
    headless.click(wb(), "unsaved.save"); // labelled "Save as...": asks where
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().fileDialog().isOpen());
    EXPECT_EQ(core::loadSessionFile(file).box("unsaved"), nullptr);
    // Another file: Save is offered.
    headless.key(wb(), GLFW_KEY_ESCAPE);
    headless.frames(wb(), 2);
    wb().guardUnsaved(
        "Open other", [] {}, dir.file("other.faultline.json"));
    headless.frames(wb(), 2);
    EXPECT_TRUE(wb().unsavedPromptOffersSave());
}

// Save as onto an existing file that is not the session's own asks before replacing it.
TEST_F(UnsavedWork, SaveAsOverAnotherFileAsksFirst) {
    openLattice();
    const std::string a = dir.file("a.faultline.json"), b = dir.file("b.faultline.json");
    wb().saveSessionAs(a);
    headless.frames(wb(), 2);
    addBox("only in b");
    wb().saveSessionAs(b);
    headless.frames(wb(), 2);
    wb().saveSessionAs(a);
    headless.frames(wb(), 2);
    ASSERT_TRUE(wb().overwritePromptOpen());
    EXPECT_TRUE(wb().overwriteLoss().empty()); // b holds all a does: only "replace it?"
    headless.click(wb(), "overwrite.replace");
    headless.frames(wb(), 3);
    EXPECT_NE(core::loadSessionFile(a).box("only in b"), nullptr);
    EXPECT_EQ(wb().sessionPath(), a);
}

TEST_F(UnsavedWork, SaveAsFromTheQuestionQuitsOnlyWhenWritten) {
    openLattice();
    addBox("b");
    wb().requestQuit();
    headless.frames(wb(), 2);
    headless.click(wb(), "unsaved.save"); // never saved: "Save as..." asks where
    headless.frames(wb(), 2);
    ASSERT_TRUE(wb().fileDialog().isOpen());
    EXPECT_FALSE(wb().quitRequested());
    const std::string file = dir.file("new.faultline.json");
    headless.key(wb(), GLFW_KEY_A, true);
    headless.type(wb(), file);
    headless.key(wb(), GLFW_KEY_ENTER);
    headless.frames(wb(), 3);
    EXPECT_TRUE(std::filesystem::exists(file)) << wb().lastMessage();
    EXPECT_TRUE(wb().quitRequested());
}

// Issue 27: a save dialog's suggested name is selected when the field takes focus (also by a
// click): what the user types replaces it (a typed path was appended to it:
// "faults.glb/tmp/.../F1.gltf").
TEST_F(UnsavedWork, TypingInASaveDialogReplacesTheSuggestedName) {
    openLattice();
    addBox("b");
    wb().requestQuit();
    headless.frames(wb(), 2);
    headless.click(wb(), "unsaved.save");
    headless.frames(wb(), 2);
    ASSERT_TRUE(wb().fileDialog().isOpen());
    const std::string file = dir.file("typed.faultline.json");
    // Click into the field, as a user does, then type: no select-all first.
    headless.click(wb(), "filedialog.name");
    headless.type(wb(), file);
    headless.key(wb(), GLFW_KEY_ENTER);
    headless.frames(wb(), 3);
    EXPECT_TRUE(std::filesystem::exists(file)) << wb().lastMessage();
}

// The test runs itself as a child process that makes changes, lets autosave write them and is
// then killed (SIGKILL: no destructor, no clean-exit record); the next start offers them back.
TEST_F(UnsavedWork, AProcessKilledWithUnsavedChangesOffersThemAtTheNextStart) {
    if (const char* child = std::getenv("FAULTLINE_UNSAVED_CHILD")) {
        (void)child;
        openLattice();
        addBox("work of the killed run");
        headless.frames(wb(), 3); // autosave (every frame here)
        std::raise(SIGKILL);
    }
    const std::string state = stateDir();
    TearDown(); // this run's workbench exits (cleanly) before the child starts on its folder
    // The child runs this test alone in a new process on the same state folder.
    std::string filter =
        "--gtest_filter=UnsavedWork.AProcessKilledWithUnsavedChangesOffersThemAtTheNextStart";
    std::string env = "FAULTLINE_UNSAVED_CHILD=1";
    std::string dirEnv = "FAULTLINE_UNSAVED_DIR=" + dir.path().string();
    char* argv[] = {const_cast<char*>("/proc/self/exe"), filter.data(), nullptr};
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) // not this run's share of the tests (it would hold none)
        if (std::strncmp(*e, "GTEST_SHARD_INDEX=", 18) != 0 &&
            std::strncmp(*e, "GTEST_TOTAL_SHARDS=", 19) != 0)
            envp.push_back(*e);
    envp.push_back(env.data());
    envp.push_back(dirEnv.data());
    envp.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv, envp.data()), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
        << "the child should have been killed; status " << status;
    // This process's own workbench (from SetUp) already looked for a recovery; a new start:
    ui::WorkbenchOptions options;
    options.stateDir = state;
    options.autosaveSeconds = 0;
    core::Session next;
    ui::Workbench restarted(next, options);
    ASSERT_TRUE(restarted.pendingRecovery().has_value());
    EXPECT_NE(core::loadSessionFile(restarted.pendingRecovery()->sessionPath)
                  .box("work of the killed run"),
              nullptr);
}
