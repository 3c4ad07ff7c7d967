#include "ui/dock/dock_layout.hpp"
#include "ui/dock/panel_ids.hpp"

#include <gtest/gtest.h>

using namespace faultline::ui;
using nlohmann::json;

namespace {

const std::vector<std::string>& known() { return panel_ids::all(); }

// The tree as nested text, e.g. h(data|v(viewports|timeline)).
std::string shape(const DockNode& n) {
    if (n.isLeaf()) {
        std::string s;
        for (const auto& t : n.tabs)
            s += (s.empty() ? "" : ",") + t;
        return s;
    }
    return std::string(n.split == SplitAxis::Horizontal ? "h(" : "v(") + shape(*n.first) + "|" +
           shape(*n.second) + ")";
}

} // namespace

TEST(DockLayout, DefaultPutsTheViewportsInTheCentre) {
    DockLayout l = DockLayout::defaultLayout();
    EXPECT_EQ(shape(l.root()),
              "h(data,boxes,thresholds|h(v(viewports|timeline)|v(histograms|faults,surfaces)))");
    for (const auto& p : known())
        EXPECT_TRUE(l.contains(p)) << p;
}

TEST(DockLayout, JsonRoundTripKeepsTreeRatiosActiveTabsAndSettings) {
    DockLayout l = DockLayout::defaultLayout();
    l.root().ratio = 0.3f;
    l.setActive("thresholds");
    l.panelSettings("histograms")["log"] = true;
    const json doc = l.toJson();
    auto back = DockLayout::fromJson(doc, known());
    ASSERT_TRUE(back);
    EXPECT_EQ(back->toJson(), doc);
    EXPECT_EQ(back->areaOf("data")->active, "thresholds");
    EXPECT_FLOAT_EQ(back->root().ratio, 0.3f);
}

TEST(DockLayout, MovingATabJoinsOrSplitsAndEmptyAreasCollapse) {
    DockLayout l = DockLayout::defaultLayout();
    ASSERT_TRUE(l.closePanel("surfaces")); // faults alone in its area
    // Onto the centre of the viewports' area: a second tab there.
    ASSERT_TRUE(l.movePanel("faults", l.areaOf("viewports")->id, DropSide::Centre));
    EXPECT_EQ(shape(l.root()),
              "h(data,boxes,thresholds|h(v(viewports,faults|timeline)|histograms))");
    EXPECT_EQ(l.areaOf("viewports")->active, "faults");
    // Onto the left edge of the timeline: the timeline's area splits side by side.
    ASSERT_TRUE(l.movePanel("histograms", l.areaOf("timeline")->id, DropSide::Left, 0.25f));
    EXPECT_EQ(shape(l.root()),
              "h(data,boxes,thresholds|v(viewports,faults|h(histograms|timeline)))");
    const DockNode* split = &l.root();
    split = split->second.get(); // v(...)
    EXPECT_FLOAT_EQ(split->second->ratio, 0.25f);
    // Onto the bottom of its own single-tab area: nothing to do.
    EXPECT_FALSE(l.movePanel("timeline", l.areaOf("timeline")->id, DropSide::Bottom));
    // A tab moved off a two-tab area onto that area's top edge.
    ASSERT_TRUE(l.movePanel("faults", l.areaOf("faults")->id, DropSide::Top));
    EXPECT_EQ(shape(l.root()),
              "h(data,boxes,thresholds|v(v(faults|viewports)|h(histograms|timeline)))");
}

TEST(DockLayout, CloseAndOpenPanels) {
    DockLayout l = DockLayout::defaultLayout();
    ASSERT_TRUE(l.closePanel("surfaces")); // faults alone in its area
    ASSERT_TRUE(l.closePanel("faults"));
    EXPECT_FALSE(l.contains("faults"));
    EXPECT_EQ(shape(l.root()), "h(data,boxes,thresholds|h(v(viewports|timeline)|histograms))");
    EXPECT_FALSE(l.closePanel("faults"));
    l.openPanel("faults"); // its default neighbours are gone: a new area on the right
    EXPECT_TRUE(l.contains("faults"));
    ASSERT_TRUE(l.closePanel("boxes"));
    l.openPanel("boxes"); // next to data, as by default
    EXPECT_EQ(l.areaOf("boxes"), l.areaOf("data"));
    for (const auto& p : known())
        l.closePanel(p);
    EXPECT_TRUE(l.root().isLeaf());
    EXPECT_TRUE(l.root().tabs.empty());
    l.openPanel("data");
    EXPECT_EQ(shape(l.root()), "data");
}

TEST(DockLayout, FromJsonRepairsOrRefuses) {
    std::string why;
    EXPECT_FALSE(DockLayout::fromJson(json::array(), known(), &why));
    EXPECT_FALSE(DockLayout::fromJson(
        {{"root", {{"split", "x"}, {"a", json::object()}, {"b", json::object()}}}}, known(), &why));
    EXPECT_EQ(why, "\"split\" must be \"h\" or \"v\"");
    EXPECT_FALSE(
        DockLayout::fromJson({{"version", 99}, {"root", {{"tabs", {"data"}}}}}, known(), &why));
    // Unknown and repeated panels are dropped, the emptied area collapses, ratios clamp.
    const json doc = {
        {"root",
         {{"split", "h"},
          {"ratio", 7},
          {"a", {{"tabs", {"data", "surfaces-of-the-future", "data"}}, {"active", "nope"}}},
          {"b", {{"split", "v"}, {"a", {{"tabs", {"data"}}}}, {"b", {{"tabs", {"faults"}}}}}}}}};
    auto l = DockLayout::fromJson(doc, known(), &why);
    ASSERT_TRUE(l);
    EXPECT_EQ(shape(l->root()), "h(data|faults)");
    EXPECT_FLOAT_EQ(l->root().ratio, 0.95f);
    EXPECT_EQ(l->areaOf("data")->active, "data");
}
