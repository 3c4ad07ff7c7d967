// Enum name tables (core/util/enum_names.hpp, issue 39): one table per enum gives both
// directions; aliases parse but never print; case folding only where asked.
#include "core/selection/cutting_box.hpp"
#include "core/session/session_state.hpp"
#include "core/util/enum_names.hpp"
#include "core/view/camera.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;

namespace {
enum class Shade { Light, Dark, Unnamed };
constexpr EnumName<Shade> kShades[] = {
    {Shade::Light, "light"}, {Shade::Dark, "dark"}, {Shade::Light, "pale"}};
} // namespace

TEST(EnumNames, BothDirectionsFromOneTable) {
    static_assert(nameIn(kShades, Shade::Dark) == "dark");
    EXPECT_EQ(nameIn(kShades, Shade::Light), "light"); // the first entry, not the alias
    EXPECT_EQ(nameIn(kShades, Shade::Unnamed), "?");
    EXPECT_EQ(nameIn(kShades, Shade::Unnamed, "none"), "none");
    EXPECT_EQ(valueIn(kShades, "pale"), Shade::Light);
    EXPECT_EQ(valueIn(kShades, "Dark"), std::nullopt);
    EXPECT_EQ(valueIn(kShades, "Dark", NameCase::Ignore), Shade::Dark);
    EXPECT_EQ(valueIn(kShades, ""), std::nullopt);
    EXPECT_EQ(namesIn(kShades), "light | dark");
    EXPECT_EQ(namesIn(kShades, " or "), "light or dark");
    EXPECT_EQ(namesIn(kShades, ", ", " or "), "light or dark");
    EXPECT_EQ(faultFilterModeNames(), "all, labelled or only");
}

// The tables behind the session's names keep what each parser accepted before.
TEST(EnumNames, TheSessionsNamesRoundTrip) {
    for (auto p : {ViewPreset::Front, ViewPreset::Back, ViewPreset::Left, ViewPreset::Side,
                   ViewPreset::Top, ViewPreset::Bottom, ViewPreset::Iso})
        EXPECT_EQ(parseViewPreset(viewPresetName(p)), p);
    EXPECT_EQ(parseViewPreset("RIGHT"), ViewPreset::Side);
    EXPECT_EQ(parseProjection("Ortho"), Projection::Orthographic);
    EXPECT_EQ(projectionName(Projection::Orthographic), "orthographic");
    EXPECT_EQ(parseBoxMode("keep"), BoxMode::Keep);
    EXPECT_EQ(parseBoxMode("Keep"), std::nullopt);
    EXPECT_EQ(boxModeName(BoxMode::Cut), "cut");
}
