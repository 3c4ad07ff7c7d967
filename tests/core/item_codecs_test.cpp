// The session items' codecs (core/session/items): what toJson writes, patch reads back; a patch
// with some fields changes only those; errors name the field, for commands and files alike.
#include "core/session/items/item_codecs.hpp"

#include <gtest/gtest.h>

namespace faultline::core {
namespace {

template <typename T> T roundTrip(const T& item) {
    T out{};
    items::patch(out, items::ItemReader(items::toJson(item)));
    items::validate(out);
    return out;
}

TEST(ItemCodecs, WhatIsWrittenReadsBack) {
    CameraState c;
    c.target = {1, -2, 3.5};
    c.distance = 42;
    c.azimuth = 123;
    c.elevation = -30;
    c.fovY = 50;
    c.orthographic = true;
    EXPECT_EQ(roundTrip(c), c);
    CuttingBox b;
    b.name = "slab";
    b.min = {0, 1, 2};
    b.max = {3, 4, 5};
    b.mode = BoxMode::Cut;
    b.enabled = false;
    EXPECT_EQ(roundTrip(b), b);
    VariableThreshold t{"strain", 0.01, 0.5, false};
    EXPECT_EQ(roundTrip(t), t);
    ViewState v = mainView();
    v.name = "right";
    v.frame = {false, 12};
    v.colorVariable = "broken_bonds";
    v.colorMap = ColorMapSpec{ColorMapKind::Bands, 12};
    v.rangeMode = RangeMode::Fixed;
    v.range = {0, 6};
    v.difference = {ColorDifference::Mode::Change, {true, -10}};
    v.camera = c;
    v.linkedCamera = false;
    v.contextPoints = true;
    EXPECT_EQ(roundTrip(v), v);
    Fault f;
    f.name = "W graben";
    f.color = {0.25f, 0.5f, 1.0f};
    f.notes = "antithetic";
    f.visible = false;
    f.ids = {3, 5, 8};
    EXPECT_EQ(roundTrip(f), f);
    for (std::int64_t id = 0; id < 5000; ++id) // packed from 4,096 members
        f.ids.push_back(100 + 3 * id);
    EXPECT_TRUE(items::toJson(f).contains("ids_packed"));
    EXPECT_EQ(roundTrip(f), f);
    SurfaceSettings st;
    st.fault = "W graben";
    st.kernel = MetaballKernel::Inverse;
    st.iso = 150;
    st.colorBy = "strain";
    st.colorRange = std::array<double, 2>{0, 0.1};
    SurfaceSettings back;
    back.fault = st.fault;
    items::patch(back, items::ItemReader(items::toJson(st)));
    items::validate(back);
    EXPECT_EQ(back, st);
}

// A view no command would make is refused from a file too, naming the field.
TEST(ItemCodecs, AViewsRulesHoldForFilesAsForCommands) {
    auto fileError = [](const char* text) {
        ViewState v;
        try {
            items::patch(v, items::ItemReader(Json::parse(text)));
            items::validate(v);
        } catch (const items::ItemError& e) {
            return items::fileMessage("views[1]", e);
        }
        return std::string("accepted");
    };
    EXPECT_EQ(fileError(R"({"name":"v","color":{"map":"rainbow"}})"),
              "views[1].color.map: names no colour map (blue-red, viridis, diverging, pastel, "
              "bands, gray)");
    EXPECT_EQ(fileError(R"({"name":"v","color":{"difference":{"mode":"change"}}})"),
              "views[1].color.difference.mode: change needs a variable");
    EXPECT_EQ(fileError(R"({"name":"v","frame":{"relative":false,"value":2.5}})"),
              "views[1].frame.value: must be a whole number");
    EXPECT_EQ(fileError(R"({"name":"v","camera":{"elevation":120}})"),
              "views[1].camera.elevation: must lie in [-90, 90]");
}

TEST(ItemCodecs, APatchChangesOnlyTheFieldsItHolds) {
    CuttingBox b{"a", {0, 0, 0}, {1, 1, 1}, BoxMode::Keep, true};
    items::patch(b, items::ItemReader(Json::parse(R"({"max":[2,3,4]})")));
    EXPECT_EQ(b.name, "a");
    EXPECT_EQ(b.min, (std::array<double, 3>{0, 0, 0}));
    EXPECT_EQ(b.max, (std::array<double, 3>{2, 3, 4}));
    EXPECT_EQ(b.mode, BoxMode::Keep);
}

TEST(ItemCodecs, ErrorsNameTheFieldForCommandsAndFiles) {
    auto errorOf = [](const char* text, auto item) -> items::ItemError {
        try {
            items::patch(item, items::ItemReader(Json::parse(text)));
            items::validate(item);
        } catch (const items::ItemError& e) {
            return e;
        }
        ADD_FAILURE() << "accepted " << text;
        return {items::ItemError::Kind::Field, "", ""};
    };
    const auto type = errorOf(R"({"elevation":"up"})", CameraState{});
    EXPECT_EQ(items::commandMessage("camera.set", type),
              "camera.set: \"elevation\" must be a finite number, found \"up\"");
    EXPECT_EQ(items::fileMessage("views[1].camera", type),
              "views[1].camera.elevation: must be a finite number");
    const auto rule = errorOf(R"({"elevation":95})", CameraState{});
    EXPECT_EQ(items::commandMessage("camera.set", rule),
              "camera.set: elevation must lie in [-90, 90]");
    EXPECT_EQ(items::fileMessage("views[0].camera", rule),
              "views[0].camera.elevation: must lie in [-90, 90]");
    const auto low = errorOf(R"({"variable":"s","low":3,"high":1})", VariableThreshold{});
    EXPECT_EQ(items::commandMessage("threshold.set", low),
              "threshold.set: low must not exceed high");
    const auto mode = errorOf(R"({"name":"b","mode":"slice"})", CuttingBox{});
    EXPECT_EQ(items::commandMessage("box.set", mode),
              "box.set: \"mode\" must be keep or cut, found \"slice\"");
}

// Commands read items through the codecs: the same rules, the same messages.
TEST(ItemCodecs, CommandsReadItemsThroughTheCodecs) {
    const CuttingBox b = items::patched(
        "box.add", CuttingBox{},
        Json::parse(R"({"op":"box.add","name":"k","min":[0,0,0],"max":[1,2,3],"mode":"cut"})"),
        {"name", "min", "max"});
    EXPECT_EQ(b.mode, BoxMode::Cut);
    EXPECT_EQ(b.max, (std::array<double, 3>{1, 2, 3}));
    try {
        items::patched("box.add", CuttingBox{},
                       Json::parse(R"({"op":"box.add","name":"k","max":[1,1,1]})"),
                       {"name", "min", "max"});
        ADD_FAILURE() << "a box without min was accepted";
    } catch (const CommandError& e) {
        EXPECT_STREQ(e.what(), "box.add: \"min\" is missing");
    }
}

} // namespace
} // namespace faultline::core
