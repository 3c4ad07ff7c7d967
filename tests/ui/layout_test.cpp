// Issue 27: every panel and window of the workbench, at 1280x800 and 1920x1080, with no text cut
// off by its window, column or button and none drawn over other text (layout_check.hpp). The
// scene is what a user has after a while on the demo: the demo's long variable names, faults
// with long names, two views side by side coloured by a change since a frame, boxes,
// thresholds, histograms and the help window.
#include "../core/test_files.hpp"
#include "headless_ui.hpp"
#include "layout_check.hpp"
#include "ui/app/theme.hpp"
#include "ui/dock/panel_ids.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <set>
#include <sstream>

namespace faultline::test {
namespace {

using core::Json;

// 4 frames of a 6x6x6 lattice with the demo's columns, extent and number lengths (a block
// about 271 x 66 x 70, coordinates with 4 digits).
std::string demoLikeDump() {
    std::string text;
    for (int t = 0; t < 4; ++t) {
        text += "ITEM: TIMESTEP\n" + std::to_string(1000 + t * 20000) +
                "\nITEM: NUMBER OF ATOMS\n216\nITEM: BOX BOUNDS pp pp pp\n0 271\n0 66\n0 70\n"
                "ITEM: ATOMS id type x y z radius strain broken_bonds layer x0 y0 z0\n";
        int id = 1;
        for (int z = 0; z < 6; ++z)
            for (int y = 0; y < 6; ++y)
                for (int x = 0; x < 6; ++x) {
                    const double px = 1 + x * 53.98 + 0.013 * t * x, py = 0.815 + y * 12.81,
                                 pz = 0.583 + z * 13.51;
                    // The last grain thrown out: its strain stretches the histogram's axis
                    // (the others fill under a thousandth of it), which offers the middle view.
                    const double strain = id == 216 ? 1.0e5 : 0.0001 + 0.5217 * (x + y) * t;
                    char row[240];
                    std::snprintf(
                        row, sizeof row, "%d %d %.4f %.4f %.4f 1 %.4f %d %d %.4f %.4f %.4f\n", id++,
                        1 + (x + y) % 3, px, py, pz, strain, (x == y) ? 4 * t : 0, z, px, py, pz);
                    text += row;
                }
    }
    return text;
}

// `layout`: a layout.set to apply first; `only`: count problems only in windows whose name holds
// one of these (empty: every window).
void checkEveryPanel(float width, float height, const char* layout = nullptr,
                     std::vector<std::string> only = {}) {
    TempDir dir;
    core::Session session;
    HeadlessUi headless(width, height);
    // The workbench's own look and font (DejaVu Sans, as the app loads it): text widths must be
    // the user's, not ImGui's narrow bitmap font's.
    ui::applyTheme(1.0f);
    ASSERT_TRUE(ui::loadFonts(1.0f)) << "DejaVu Sans is missing (scripts/setup.sh installs it)";
    {
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    }
    ui::WorkbenchOptions options;
    auto wb = std::make_unique<ui::Workbench>(session, options);
    headless.frames(*wb, 2);
    {
        std::FILE* f = std::fopen(dir.file("demo_like.dump").c_str(), "wb");
        const std::string text = demoLikeDump();
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
    }
    wb->opener().openData({dir.file("demo_like.dump")});
    headless.settle(*wb);
    ASSERT_NE(session.dataset(), nullptr);
    if (layout) {
        session.apply(Json::parse(layout));
        headless.settle(*wb);
    }

    std::ostringstream found;
    std::set<std::string> seen; // a window shows the same problem whichever panel is in front
    std::size_t count = 0;
    auto checkAll = [&](const char* scene) {
        for (const std::string& panel : ui::panel_ids::all()) {
            headless.showPanel(*wb, panel);
            headless.settle(*wb);
            for (const LayoutProblem& p : layoutProblems(ImGui::GetDrawData())) {
                // The Faults panel's name field holds the long name and scrolls, as every text
                // field does (ImGui trims its text on the CPU): not a cut-off label.
                if (p.what.rfind("\"West-dippinggraben", 0) == 0 &&
                    p.what.find("(trimmed to its box)") != std::string::npos &&
                    p.window.find("content.faults") != std::string::npos)
                    continue;
                if (!only.empty() &&
                    std::none_of(only.begin(), only.end(), [&](const std::string& w) {
                        return p.window.find(w) != std::string::npos;
                    }))
                    continue;
                if (seen.insert(p.window + p.what).second) {
                    ++count;
                    found << "  [" << scene << ", " << panel << " in front] " << p.window << ": "
                          << p.what << "\n";
                }
            }
        }
    };
    checkAll("just opened"); // the empty panels' hints
    for (
        const char* op : {
            R"({"op":"fault.create","name":"West-dipping graben boundary fault","ids":[1,8,15,22,29,36]})",
            R"({"op":"fault.create","name":"F2","ids":[43,50,57,64]})",
            R"({"op":"box.add","name":"Central slab through the graben","min":[50,0,0],"max":[220,70,70]})",
            R"({"op":"threshold.add","variable":"broken_bonds","low":2,"high":12})",
            R"({"op":"surface.set","fault":"F2","kernel":"compact","iso":0.3,"visible":true})",
            R"({"op":"view.add","name":"view 2","frame":1})",
            // Three views side by side: at 640 pixels each header takes two rows.
            R"({"op":"view.add","name":"view 3","frame":2})",
            R"({"op":"frame.set","frame":3})",
            R"({"op":"color.set","view":"main","variable":"broken_bonds","difference":"change","since_frame":1})",
            // Strain from motion: the lattice's spheres are too far apart to have neighbours
            // within the cutoff, so every value is NaN and the histogram says how many have
            // none. (The automatic cutoff, 1.5 diameters, is refused here for that reason.)
            R"({"op":"strain.add","since_offset":-1,"prefix":"inc_","cutoff":3})",
        })
        session.apply(Json::parse(op));
    wb->selection().faults = {"F2"};
    // The histograms a user picked, the thresholded one first (its title shows the bounds).
    wb->layout().panelSettings(ui::panel_ids::kHistograms)["variables"] = {
        "broken_bonds", "type", "strain", "inc_shear_strain"};
    wb->showHelp();
    headless.settle(*wb);
    checkAll("after an hour");
    headless.showPanel(*wb, ui::panel_ids::kHistograms);
    headless.settle(*wb);
    EXPECT_TRUE(headless.has(*wb, "histogram.strain.offer-middle")) << "the button was checked";
    // The long-named fault picked, with a surface: its settings and metrics under its name.
    session.apply(Json::parse(
        R"({"op":"surface.set","fault":"West-dipping graben boundary fault","kernel":"compact","iso":0.3,"visible":true})"));
    wb->selection().faults = {"West-dipping graben boundary fault"};
    wb->showHelp();
    headless.settle(*wb);
    checkAll("a long-named fault picked");
    EXPECT_EQ(count, 0u) << "at " << width << "x" << height << ":\n" << found.str();
}

TEST(Layout, NoTextIsCutOffOrOverlapsAt1280x800) { checkEveryPanel(1280, 800); }
TEST(Layout, NoTextIsCutOffOrOverlapsAt1920x1080) { checkEveryPanel(1920, 1080); }
// Issue 41, item 12: a small window (a laptop's split screen).
TEST(Layout, NoTextIsCutOffOrOverlapsAt640x420) { checkEveryPanel(640, 420); }

// A walkthrough's own layout at 640 pixels: three columns, the left one 128 pixels wide. The
// threshold's name and the Data panel's values vanished there; then (issue 41, last
// walkthrough) the Data panel's "Strain from motion" header and radio labels ran past the
// edge, the Faults panel's "Remove the visible spheres", and three views a third of 300 px
// wide put the frame binding's "..." under the close button. Every window is checked.
TEST(Layout, NoTextIsCutOffInANarrowColumnAt640x420) {
    checkEveryPanel(640, 420, R"({"op":"layout.set","layout":{"root":{"split":"h","ratio":0.2,
        "a":{"tabs":["data","thresholds","boxes"]},
        "b":{"split":"h","ratio":0.6,
            "a":{"split":"v","ratio":0.7,"a":{"tabs":["viewports"]},"b":{"tabs":["timeline"]}},
            "b":{"split":"v","ratio":0.4,"a":{"tabs":["histograms"]},"b":{"tabs":["faults","surfaces"]}}}}}})",
                    {});
}

// The checker itself: it finds a label cut off by its window and two texts drawn over each other.
TEST(Layout, TheCheckerFindsCutOffAndOverlappingText) {
    const HeadlessUi context(800, 600); // an ImGui context with its font atlas built
    auto frame = [&](bool cut, bool overlap, bool fits) {
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(10, 10));
        ImGui::SetNextWindowSize(ImVec2(120, 200));
        ImGui::Begin("narrow", nullptr, ImGuiWindowFlags_NoSavedSettings);
        if (fits)
            ImGui::TextUnformatted("short");
        if (cut)
            ImGui::TextUnformatted("a label far too long for this window");
        if (overlap) {
            ImGui::TextUnformatted("left text");
            ImGui::SameLine(30);
            ImGui::TextUnformatted("over it");
        }
        ImGui::End();
        ImGui::Render();
        return layoutProblems(ImGui::GetDrawData());
    };
    frame(false, false, true);
    EXPECT_TRUE(frame(false, false, true).empty());
    const auto cut = frame(true, false, false);
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_NE(cut[0].what.find("wider than the window"), std::string::npos) << cut[0].what;
    const auto over = frame(false, true, false);
    ASSERT_EQ(over.size(), 1u);
    EXPECT_NE(over[0].what.find("overlap"), std::string::npos) << over[0].what;
    // A button drawn over a label hides it.
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(10, 10));
    ImGui::SetNextWindowSize(ImVec2(300, 200));
    ImGui::Begin("covered", nullptr, ImGuiWindowFlags_NoSavedSettings);
    ImGui::TextUnformatted("a label under a button");
    ImGui::SameLine(20);
    ImGui::Button("##over", ImVec2(80, 0));
    ImGui::End();
    ImGui::Render();
    const auto covered = layoutProblems(ImGui::GetDrawData());
    ASSERT_EQ(covered.size(), 1u);
    EXPECT_NE(covered[0].what.find("hidden under a shape"), std::string::npos) << covered[0].what;
}

} // namespace
} // namespace faultline::test

namespace faultline::test {
// Issue 41, item 12: in a small window every side panel is one column of tabs; those that do
// not fit are reached through the list at the end of the tab bar.
TEST(Layout, ASmallWindowReachesEveryPanelThroughTheTabList) {
    core::Session session;
    {
        HeadlessUi headless(640, 420);
        ui::WorkbenchOptions options;
        auto wb = std::make_unique<ui::Workbench>(session, options);
        headless.frames(*wb, 3);
        ui::DockNode* column = wb->layout().areaOf(ui::panel_ids::kFaults);
        ASSERT_NE(column, nullptr);
        EXPECT_EQ(column, wb->layout().areaOf(ui::panel_ids::kData)); // one column
        EXPECT_FALSE(headless.has(*wb, "tab." + std::string(ui::panel_ids::kFaults)));
        const std::string more = "tabs.more." + std::to_string(column->id);
        ASSERT_TRUE(headless.has(*wb, more));
        headless.click(*wb, more);
        headless.frames(*wb, 2);
        headless.click(*wb, "tabs.list." + std::string(ui::panel_ids::kFaults));
        headless.frames(*wb, 2);
        EXPECT_EQ(wb->layout().areaOf(ui::panel_ids::kFaults)->active, ui::panel_ids::kFaults);
        EXPECT_TRUE(headless.has(*wb, "tab." + std::string(ui::panel_ids::kFaults))); // now shown
    }
    // A wide window keeps the two columns.
    ui::WorkbenchOptions options;
    HeadlessUi wide(1600, 1000);
    auto wb2 = std::make_unique<ui::Workbench>(session, options);
    wide.frames(*wb2, 3);
    EXPECT_NE(wb2->layout().areaOf(ui::panel_ids::kFaults),
              wb2->layout().areaOf(ui::panel_ids::kData));
}
} // namespace faultline::test
