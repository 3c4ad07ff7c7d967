// core::colorView (issue 39): the one rule for what a view's spheres are coloured by and over
// which range, shared by the workbench's views, figures and movies. On the lattice (strain =
// x / 3 + frame, x in 0..3, three frames), with sources that answer at once.
#include "core/data/dataset.hpp"
#include "core/model/frame_difference.hpp"
#include "core/session/color_range.hpp"
#include "core/session/view_colors.hpp"
#include "lattice_dump.hpp"
#include "test_files.hpp"

#include <gtest/gtest.h>

using namespace faultline::core;
using faultline::test::TempDir;

namespace {

struct Lattice {
    TempDir dir;
    std::shared_ptr<Dataset> ds =
        Dataset::open({dir.write("lattice.dump", faultline::test::latticeDump())});
    int allFramesAsked = 0;
    bool referenceLoaded = true;

    ViewColorSources sources() {
        ViewColorSources s;
        s.frame = [this](std::size_t f) {
            return referenceLoaded ? ds->frame(f) : std::shared_ptr<const Frame>();
        };
        s.difference = [](const std::shared_ptr<const Frame>& now,
                          const std::shared_ptr<const Frame>& ref, ColorDifference::Mode mode,
                          const std::string& variable) {
            return std::make_shared<const AttributeColumn>(
                mode == ColorDifference::Mode::Change ? variableChange(*now, *ref, variable)
                                                      : displacementSince(*now, *ref));
        };
        s.allFrames = [this](const ViewState& v, const std::string&, ValueRange inFrame) {
            ++allFramesAsked;
            return colorRangeOverFrames(*ds, v).value_or(inFrame);
        };
        s.visibleRange = [](const Frame& f, const VisibilityResult& vis,
                            const std::string& variable,
                            bool percentiles) -> std::optional<ValueRange> {
            if (const auto r = percentiles ? maskedQuantiles(f, variable, vis.mask, 0.01, 0.99)
                                           : maskedRange(f, variable, vis.mask))
                return ValueRange{r->first, r->second};
            return std::nullopt;
        };
        return s;
    }
    ViewColoring color(const ViewState& v, std::size_t shown,
                       const VisibilityResult* visibility = nullptr) {
        return colorView(v, shown, ds->frameCount(), ds->frame(shown), visibility, sources());
    }
};

ViewState strainView() {
    ViewState v;
    v.name = "main";
    v.colorVariable = "strain";
    return v;
}

// The spheres with x <= `maxX` visible.
VisibilityResult upTo(const Frame& f, float maxX) {
    VisibilityResult r;
    r.mask.resize(f.size());
    for (std::size_t i = 0; i < f.size(); ++i)
        r.visibleCount += r.mask[i] = f.x[i] <= maxX;
    return r;
}

} // namespace

TEST(ViewColors, AVariableSpansItsFrameTheSpheresShownOrEveryFrame) {
    Lattice l;
    ViewState v = strainView();
    ViewColoring c = l.color(v, 1);
    EXPECT_EQ(c.title, "strain");
    EXPECT_EQ(c.column, nullptr); // the variable's own column
    EXPECT_DOUBLE_EQ(c.range.low, 1.0);
    EXPECT_DOUBLE_EQ(c.range.high, 2.0);
    // "this frame's" over the spheres shown: x <= 1 gives strain 1 .. 1 + 1/3.
    const VisibilityResult west = upTo(*l.ds->frame(1), 1.0f);
    c = l.color(v, 1, &west);
    EXPECT_DOUBLE_EQ(c.range.low, 1.0);
    EXPECT_NEAR(c.range.high, 1.0 + 1.0 / 3.0, 1e-6);
    EXPECT_EQ(l.allFramesAsked, 0);
    // All frames: 0 .. 3, whichever spheres are shown.
    v.rangeMode = RangeMode::AllFrames;
    c = l.color(v, 1, &west);
    EXPECT_DOUBLE_EQ(c.range.low, 0.0);
    EXPECT_DOUBLE_EQ(c.range.high, 3.0);
    EXPECT_EQ(l.allFramesAsked, 1);
    // Fixed wins over everything.
    v.rangeMode = RangeMode::Fixed;
    v.range = {-1, 5};
    c = l.color(v, 1, &west);
    EXPECT_EQ(c.range, (ValueRange{-1, 5}));
}

// "percentile": the 1st to 99th percentile of the spheres shown, so that a few grains thrown out
// of a model (strain from motion in the hundreds) leave the others their colours.
TEST(ViewColors, PercentilesLeaveAFewExtremesOut) {
    Lattice l; // for its sources
    auto f = std::make_shared<Frame>();
    AttributeColumn shear;
    shear.name = "shear";
    shear.type = ColumnType::Float32;
    for (int i = 0; i < 400; ++i) {
        f->ids.push_back(i + 1);
        f->x.push_back(float(i));
        f->y.push_back(0.0f);
        f->z.push_back(0.0f);
        f->radius.push_back(0.5f);
        // 0 .. 0.99 four times over, and two grains far out (x = 0 and 399).
        shear.floats.push_back(i == 0 || i == 399 ? 500.0f : float(i % 100) / 100.0f);
    }
    f->attributes.push_back(shear);
    f->finalize();
    ViewState v;
    v.name = "main";
    v.colorVariable = "shear";
    VisibilityResult all;
    all.mask.assign(f->size(), 1);
    all.visibleCount = f->size();
    auto color = [&](const VisibilityResult* vis) {
        return colorView(v, 0, 1, f, vis, l.sources());
    };
    EXPECT_DOUBLE_EQ(color(&all).range.high, 500.0); // this frame's min to max
    v.rangeMode = RangeMode::Percentile;
    ViewColoring c = color(&all);
    EXPECT_NEAR(c.range.low, 0.0, 0.02);
    EXPECT_NEAR(c.range.high, 0.99, 0.02);
    EXPECT_EQ(c.title, "shear");
    // Over the spheres shown: x < 200, whose values are 0 .. 0.99 and one far out.
    VisibilityResult west = all;
    for (std::size_t i = 200; i < f->size(); ++i)
        west.mask[i] = 0;
    west.visibleCount = 200;
    c = color(&west);
    EXPECT_NEAR(c.range.low, 0.0, 0.02);
    EXPECT_NEAR(c.range.high, 0.99, 0.02);
    // No visibility yet: the frame's min to max until it comes.
    EXPECT_DOUBLE_EQ(color(nullptr).range.high, 500.0);
    // A difference colouring spans every frame, whatever the mode.
    EXPECT_EQ(effectiveRangeMode(v), RangeMode::Percentile);
    v.difference.mode = ColorDifference::Mode::Change;
    EXPECT_EQ(effectiveRangeMode(v), RangeMode::AllFrames);
}

TEST(ViewColors, AChangeIsSymmetricOverEveryFrameADisplacementStartsAtZero) {
    Lattice l;
    ViewState v = strainView();
    v.difference.mode = ColorDifference::Mode::Change;
    v.difference.reference = {false, 0}; // since frame 0
    ViewColoring c = l.color(v, 2);
    ASSERT_NE(c.column, nullptr);
    EXPECT_EQ(c.title, colorTitle(v, 0));
    EXPECT_EQ(c.reference, 0u);
    EXPECT_FLOAT_EQ(c.column->floats[0], 2.0f); // strain rose by 2 in two frames
    // Over every frame the change spans 0 .. 2: symmetric about zero, -2 .. 2, even with
    // "this frame's" chosen (a change means the same at every frame, issue 41).
    EXPECT_DOUBLE_EQ(c.range.low, -2.0);
    EXPECT_DOUBLE_EQ(c.range.high, 2.0);
    v.difference.mode = ColorDifference::Mode::Displacement;
    c = l.color(v, 2);
    EXPECT_EQ(c.range, (ValueRange{-0.5, 0.5})); // nothing moved: 0 .. 0, widened
}

TEST(ViewColors, OneColourUntilTheReferenceFrameIsHereOrWithoutTheVariable) {
    Lattice l;
    ViewState v = strainView();
    v.difference.mode = ColorDifference::Mode::Change;
    l.referenceLoaded = false;
    ViewColoring c = l.color(v, 2);
    EXPECT_TRUE(c.title.empty());
    EXPECT_EQ(c.column, nullptr);
    EXPECT_EQ(c.range, (ValueRange{0, 1}));
    l.referenceLoaded = true;
    v.colorVariable = "strian"; // the frames lack it: one colour, not an error
    c = l.color(v, 2);
    EXPECT_TRUE(c.title.empty());
    EXPECT_EQ(c.column, nullptr);
}

TEST(ViewColors, ARangeOfOneValueIsWidened) {
    Lattice l;
    ViewState v = strainView();
    v.colorVariable = "layer";
    const VisibilityResult bottom = [&] {
        VisibilityResult r;
        const auto f = l.ds->frame(0);
        r.mask.resize(f->size());
        for (std::size_t i = 0; i < f->size(); ++i)
            r.visibleCount += r.mask[i] = f->z[i] == 0.0f;
        return r;
    }();
    const ViewColoring c = l.color(v, 0, &bottom); // layer 0 alone
    EXPECT_EQ(c.range, (ValueRange{-0.5, 0.5}));
}
