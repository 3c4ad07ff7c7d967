// Movies and PNG sequences: the journal's render with "frames", H.264 read back with libavformat,
// the frame selection of a sharded replay, and the refusals.
#include "../core/test_files.hpp"
#include "core/session/color_range.hpp"
#include "core/session/session.hpp"
#include "core/surface/surface_cache.hpp"
#include "core/synth/demo_model.hpp"
#include "gl_required.hpp"
#include "headless_ui.hpp"
#include "panel_fixture.hpp"
#include "ui/render/movie_writer.hpp"
#include "ui/render/offscreen.hpp"
#include "ui/viewport/session_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace faultline;
using faultline::core::Json;
using faultline::test::PanelTest;

namespace {

ui::RgbaImage solid(int w, int h, std::uint8_t red) {
    ui::RgbaImage img{w, h, {}};
    img.pixels.resize(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4) {
        img.pixels[i] = red;
        img.pixels[i + 1] = static_cast<std::uint8_t>(i / 4 % 251);
        img.pixels[i + 2] = 40;
        img.pixels[i + 3] = 255;
    }
    return img;
}

// A session on the 3-frame lattice with the render op, or null without OpenGL.
class MovieTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string why;
        if (!ui::sharedOffscreenContext(why))
            FAULTLINE_NEED_GL("no OpenGL context: " << why);
        ui::registerRenderOp(session);
        session.setBaseDir(dir.path().string());
        session.apply(
            {{"op", "data.open"}, {"paths", {test::writeLattice(dir.file("lattice.dump"))}}});
        session.apply({{"op", "color.set"}, {"view", "main"}, {"variable", "strain"}});
    }
    test::TempDir dir;
    core::Session session;
};

} // namespace

TEST(MovieWriter, WritesH264ThatLibavformatReadsBackFrameByFrame) {
    test::TempDir dir;
    const std::string path = dir.file("seven.mp4");
    {
        ui::MovieWriter movie(path, {100, 61, 12, 20}); // odd height: rounded up to 62
        for (int k = 0; k < 7; ++k)
            movie.add(solid(100, 61, static_cast<std::uint8_t>(30 * k)));
        movie.finish();
        EXPECT_EQ(movie.framesWritten(), 7u);
    }
    const ui::MovieProbe probe = ui::probeMovie(path);
    EXPECT_EQ(probe.frames, 7u);
    EXPECT_EQ(probe.width, 100);
    EXPECT_EQ(probe.height, 62);
    EXPECT_EQ(probe.codec, "h264");
}

TEST(MovieWriter, RefusesWhatItCannotWriteSayingWhere) {
    test::TempDir dir;
    EXPECT_THROW(ui::MovieWriter(dir.file("no/such/folder/m.mp4"), {}), std::runtime_error);
    ui::MovieWriter movie(dir.file("m.mp4"), {64, 64, 10, 20});
    EXPECT_THROW(movie.add(solid(32, 32, 0)), std::invalid_argument);
    EXPECT_THROW(ui::probeMovie(dir.file("missing.mp4")), std::runtime_error);
    dir.write("x/not.mp4", "this is not a movie");
    EXPECT_THROW(ui::probeMovie(dir.file("x/not.mp4")), std::runtime_error);
}

TEST_F(MovieTest, AFrameRangeBecomesAMovieWithOneVideoFramePerDataFrame) {
    session.apply(
        Json::parse(R"({"op":"render","path":"out/run.mp4","size":[160,90],"frames":[0,2]})"));
    const ui::MovieProbe probe = ui::probeMovie(dir.file("out/run.mp4"));
    EXPECT_EQ(probe.frames, 3u);
    EXPECT_EQ(probe.width, 160);
    EXPECT_EQ(probe.height, 90);
    session.apply(Json::parse(
        R"({"op":"render","path":"out/odd.mp4","size":[160,90],"frames":[0,2],"step":2,"fps":5})"));
    EXPECT_EQ(ui::probeMovie(dir.file("out/odd.mp4")).frames, 2u);
}

TEST_F(MovieTest, APatternPathWritesAPngPerFrameNamedByItsNumber) {
    session.apply(
        Json::parse(R"({"op":"render","path":"seq/f%03d.png","size":[64,48],"frames":[1,2]})"));
    EXPECT_FALSE(std::filesystem::exists(dir.file("seq/f000.png")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("seq/f001.png")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("seq/f002.png")));
    EXPECT_EQ(ui::framePath("a/%d_b.png", 7), "a/7_b.png");
    EXPECT_EQ(ui::framePath("a/%05d.png", 42), "a/00042.png");
    EXPECT_TRUE(ui::isFrameSequencePattern("x/frame_%04d.png"));
    EXPECT_FALSE(ui::isFrameSequencePattern("x/frame.png"));
    EXPECT_FALSE(ui::isFrameSequencePattern("x/%d_%d.png"));
}

TEST_F(MovieTest, AShardRendersOnlyItsFrames) {
    core::FrameSelection shard;
    shard.shard = 1;
    shard.shards = 2; // frames 1, 3, ...
    session.setFrameSelection(shard);
    session.apply(
        Json::parse(R"({"op":"render","path":"sh/f%d.png","size":[64,48],"frames":[0,2]})"));
    EXPECT_FALSE(std::filesystem::exists(dir.file("sh/f0.png")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("sh/f1.png")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("sh/f2.png")));
}

TEST_F(MovieTest, BadFrameRangesAndPathsAreRefusedBeforeAnythingIsWritten) {
    auto refused = [&](const char* text, const std::string& message) {
        try {
            session.apply(Json::parse(text));
            ADD_FAILURE() << "accepted: " << text;
        } catch (const core::CommandError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    refused(R"({"op":"render","path":"m.mp4","frames":[0,9]})", "must lie within 0..2");
    refused(R"({"op":"render","path":"m.mp4","frames":[2,1]})", "first <= last");
    refused(R"({"op":"render","path":"m.png","frames":[0,2]})", "must end in .mp4");
    refused(R"({"op":"render","path":"m.mp4","frames":[0]})", "[first, last]");
    refused(R"({"op":"render","path":"m.mp4","frames":[0,2],"step":0})", "\"step\"");
    refused(R"({"op":"render","path":"m.png","step":2})", "needs \"frames\"");
    refused(R"({"op":"render","path":"m.mp4","frames":[0,2],"frame":1})", "not both");
    EXPECT_FALSE(std::filesystem::exists(dir.file("m.mp4")));
}

// File > Export > Movie in the workbench: a frame per UI frame with progress, journalled as the
// render op once written; Cancel leaves a playable movie of what was done and no journal line.
TEST_F(PanelTest, TheWorkbenchWritesAMovieFrameByFrameAndJournalsIt) {
    std::string why;
    if (!ui::sharedOffscreenContext(why))
        FAULTLINE_NEED_GL("no OpenGL context: " << why);
    openLattice();
    wb().showMovieOptions();
    EXPECT_EQ(wb().movieOptions.first, 0);
    EXPECT_EQ(wb().movieOptions.last, 2);
    wb().movieOptions.width = 160;
    wb().movieOptions.height = 90;
    const std::size_t before = session.journal().size();
    wb().exportMovie(dir.file("out/lattice"));
    ASSERT_TRUE(wb().movieRunning()) << wb().lastMessage();
    EXPECT_EQ(wb().movieProgress().second, 3u);
    for (int k = 0; k < 200 && wb().movieRunning(); ++k) {
        wb().frames().waitIdle();
        headless.frames(wb(), 1);
    }
    ASSERT_FALSE(wb().movieRunning());
    EXPECT_FALSE(wb().lastMessageIsError()) << wb().lastMessage();
    EXPECT_EQ(ui::probeMovie(dir.file("out/lattice.mp4")).frames, 3u);
    ASSERT_EQ(session.journal().size(), before + 1);
    const Json& cmd = session.journal().back();
    EXPECT_EQ(cmd.value("op", ""), "render");
    EXPECT_EQ(cmd["frames"], Json::parse("[0,2]"));
    EXPECT_EQ(cmd["path"], dir.file("out/lattice.mp4"));

    // PNG frames, cancelled after the first: nothing journalled.
    wb().movieOptions.pngFrames = true;
    wb().exportMovie(dir.file("out/f.png"));
    ASSERT_TRUE(wb().movieRunning());
    for (int k = 0; k < 200 && wb().movieProgress().first < 1; ++k) {
        wb().frames().waitIdle();
        headless.frames(wb(), 1);
    }
    wb().cancelMovie();
    EXPECT_FALSE(wb().movieRunning());
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/f_0000.png")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("out/f_0002.png")));
    EXPECT_EQ(session.journal().size(), before + 1);
    EXPECT_NE(wb().lastMessage().find("cancelled"), std::string::npos) << wb().lastMessage();
}

// Issue 41, item 4: File > Export > Screenshot captured the closing file dialog. It renders the
// main view offscreen now, at the view's size on screen, with no panel or dialog in it.
TEST_F(PanelTest, TheScreenshotIsTheMainViewRenderedOffscreen) {
    std::string why;
    if (!ui::sharedOffscreenContext(why))
        FAULTLINE_NEED_GL("no OpenGL context: " << why);
    ui::registerRenderOp(session);
    openLattice();
    const auto view = headless.rect(wb(), "view.image.main");
    const std::string path = dir.file("shot.png");
    wb().screenshotMainView(path);
    headless.frames(wb(), 2);
    ASSERT_FALSE(session.journal().empty());
    const Json cmd = session.journal().back(); // journalled like a replay's render
    ASSERT_EQ(cmd["op"], "render") << cmd.dump();
    EXPECT_EQ(cmd["view"], "main");
    EXPECT_EQ(cmd["size"][0].get<int>(), static_cast<int>(std::lround(view.x1 - view.x0)));
    ASSERT_TRUE(std::filesystem::exists(path)) << wb().lastMessage();
    EXPECT_NE(wb().lastMessage().find("Saved the main view"), std::string::npos);
}

// Issue 41: the figure was always the view's size on screen. Its options window sets a preset
// or typed size and a transparent background, which the render op records.
TEST_F(PanelTest, TheFigureTakesASizeAndATransparentBackground) {
    std::string why;
    if (!ui::sharedOffscreenContext(why))
        FAULTLINE_NEED_GL("no OpenGL context: " << why);
    ui::registerRenderOp(session);
    openLattice();
    wb().showFigureOptions();
    headless.frames(wb(), 2);
    headless.click(wb(), "figure.size.custom");
    headless.retype(wb(), "figure.width", "320", GLFW_KEY_TAB);
    headless.retype(wb(), "figure.height", "200", GLFW_KEY_TAB);
    headless.click(wb(), "figure.transparent");
    headless.frames(wb(), 2);
    EXPECT_EQ(wb().figureSize(), (std::pair<int, int>{320, 200}));
    headless.click(wb(), "figure.save"); // the file dialog opens in its place
    headless.frames(wb(), 2);
    EXPECT_FALSE(headless.has(wb(), "figure.save"));
    const std::string path = dir.file("figure.png");
    wb().screenshotMainView(path); // what the dialog's path leads to
    headless.frames(wb(), 2);
    const Json cmd = session.journal().back();
    ASSERT_EQ(cmd["op"], "render") << cmd.dump();
    EXPECT_EQ(cmd["size"], (Json{320, 200}));
    EXPECT_EQ(cmd["transparent"], true);
    ASSERT_TRUE(std::filesystem::exists(path)) << wb().lastMessage();
    // The presets.
    wb().figureOptions.size = 2;
    EXPECT_EQ(wb().figureSize(), (std::pair<int, int>{3840, 2160}));
}

// Walkthrough of issue 41: a movie of some frames coloured by a change took its range over
// those frames only (frames 0-30: +-1.8, where the view, a figure and the whole run's movie
// show +-3.77). It now takes the range over every frame, as they do (the lattice's strain rises
// by one a frame: over frame 1 alone the change since frame 0 spans +-1, over all frames +-2).
TEST_F(MovieTest, AMovieOfSomeFramesTakesTheRangeOfEveryFrame) {
    session.apply(
        Json::parse(R"({"op":"color.set","view":"main","difference":"change","since_frame":0})"));
    ui::SequenceRequest request;
    request.figure.path = dir.file("seq/m%d.png");
    request.first = request.last = 1;
    const ui::FrameSequence movie(session, request);
    const auto all = core::colorRangeOverFrames(*session.dataset(), session.state().views[0]);
    ASSERT_TRUE(movie.colorRange().has_value());
    ASSERT_TRUE(all.has_value());
    EXPECT_EQ(*movie.colorRange(), *all);
    EXPECT_EQ(all->low, -2.0);
    EXPECT_EQ(all->high, 2.0);
}

// Walkthrough of issue 41, item 8: the movie's dialog opened in the folder the workbench was
// started in whatever the last export, and an unsaved session on the built-in demo offered the
// demo's folder among the application's data. Exports now open where the last one went, else
// beside the session, else beside the data; for the demo, in the launch folder.
TEST_F(PanelTest, ExportDialogsOpenWhereTheLastExportWent) {
    openLattice();
    EXPECT_EQ(wb().exportFolder(),
              std::filesystem::path(dir.file("lattice.dump")).parent_path().string());
    wb().showMovieOptions();
    headless.frames(wb(), 2);
    headless.click(wb(), "movie.save");
    headless.frames(wb(), 2);
    ASSERT_TRUE(wb().fileDialog().isOpen());
    EXPECT_EQ(std::filesystem::weakly_canonical(wb().fileDialog().directory()),
              std::filesystem::weakly_canonical(wb().exportFolder()));
    headless.key(wb(), GLFW_KEY_ESCAPE);
    headless.frames(wb(), 2);

    // Data in the demo's folder: the launch folder instead.
    const std::string home = dir.file("data-home");
    const char* old = std::getenv("XDG_DATA_HOME");
    const std::string saved = old ? old : "";
    setenv("XDG_DATA_HOME", home.c_str(), 1);
    std::filesystem::create_directories(core::demoModelFolder());
    const std::string demo = core::demoModelFolder() + "/block.dump";
    std::filesystem::copy_file(dir.file("lattice.dump"), demo);
    wb().opener().openData({demo});
    headless.settle(wb());
    EXPECT_EQ(wb().exportFolder(), std::filesystem::current_path().string());
    if (old)
        setenv("XDG_DATA_HOME", saved.c_str(), 1);
    else
        unsetenv("XDG_DATA_HOME");
}

// A figure after surface.build draws the surface the op built (the session keeps it for the
// frame); the next frame of a movie builds its own.
TEST_F(MovieTest, AFigureDrawsTheSurfaceSurfaceBuildMade) {
    session.apply(Json::parse(R"({"op":"fault.create","name":"F1","from":"visible"})"));
    session.apply(Json::parse(
        R"({"op":"surface.build","fault":"F1","kernel":"compact","voxel":0.25,"iso":0.5})"));
    const core::SurfaceCache& cache = session.surfaceCache();
    EXPECT_EQ(cache.counters().builds, 1u);
    session.apply(Json::parse(R"({"op":"render","path":"out/s.png","size":[64,48]})"));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/s.png")));
    EXPECT_EQ(cache.counters().builds, 1u);
    EXPECT_EQ(cache.counters().hits, 1u);
    session.apply(
        Json::parse(R"({"op":"render","path":"seq/s%d.png","size":[64,48],"frames":[1,2]})"));
    EXPECT_TRUE(std::filesystem::exists(dir.file("seq/s2.png")));
    EXPECT_EQ(cache.counters().builds, 3u);
}

// A figure of a frame where the colour variable has no value (incremental strain on the first
// frame, which has no frame before it) shows grey spheres without a legend, as the workbench's
// views do; the next frame's figure has its legend. Counted as pixels unlike the background in
// the image's rightmost tenth, where the legend's bar and labels stand.
TEST_F(MovieTest, AFigureOfAFrameWithoutValuesDrawsNoLegend) {
    session.apply(Json::parse(R"({"op":"strain.add","since_offset":-1,"prefix":"inc_"})"));
    session.apply(Json::parse(R"({"op":"color.set","view":"main","variable":"inc_shear_strain"})"));
    auto legendPixels = [&](std::size_t frame) {
        ui::FigureRequest request;
        request.width = 640;
        request.height = 360;
        request.frame = frame;
        const ui::RgbaImage img = ui::renderSessionImage(session, request);
        const std::uint8_t* corner = &img.pixels[std::size_t(img.width - 1) * 4];
        std::size_t n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = img.width * 9 / 10; x < img.width; ++x) {
                const std::uint8_t* p = &img.pixels[(std::size_t(y) * img.width + x) * 4];
                n += std::abs(p[0] - corner[0]) + std::abs(p[1] - corner[1]) +
                         std::abs(p[2] - corner[2]) >
                     30;
            }
        return n;
    };
    EXPECT_EQ(legendPixels(0), 0u) << "a legend for a variable without values";
    EXPECT_GT(legendPixels(1), 100u) << "no legend where the variable has values";
}
