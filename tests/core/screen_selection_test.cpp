// Rectangle and lasso selection on a view: a 5 x 5 sheet of spheres (ids 101..125) seen from
// above through an orthographic 100 x 100 pixel view, where sphere (i, j) sits at pixel
// (10 i + 5, 95 - 10 j); exact ids for rectangles, concave and self-crossing lassos.
#include "core/view/screen_selection.hpp"

#include "fault_test_support.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace faultline::core;
using faultline::core::testing::frameOf;
using faultline::core::testing::Sphere;

namespace {

// Sphere (i, j), i east and j north in 0..4, has id 101 + i + 5 j and centre (i + 0.5, j + 0.5, 0).
Frame sheet() {
    std::vector<Sphere> s;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i)
            s.push_back({101 + i + 5 * j, i + 0.5, j + 0.5, 0.0});
    return frameOf(s);
}

// World x, y in [0, 10] fill the view; the camera looks down.
ScreenMapping topView() { return {glm::ortho(0.0, 10.0, 0.0, 10.0, -1.0, 1.0), {100.0, 100.0}}; }

std::vector<std::int64_t> idsOfRows(const Frame& f, const std::vector<std::uint32_t>& rows) {
    std::vector<std::int64_t> ids;
    for (std::uint32_t r : rows)
        ids.push_back(f.ids[r]);
    return ids;
}

std::int64_t id(int i, int j) { return 101 + i + 5 * j; }

} // namespace

TEST(ScreenSelection, ProjectsToPixelsFromTheTopLeft) {
    glm::dvec2 p;
    ASSERT_TRUE(projectToScreen(topView(), 2.5, 0.5, 0.0, p));
    EXPECT_NEAR(p.x, 25.0, 1e-9);
    EXPECT_NEAR(p.y, 95.0, 1e-9);
    EXPECT_FALSE(projectToScreen(topView(), 2.5, 0.5, 3.0, p)); // outside the depth range
}

TEST(ScreenSelection, RectangleTakesTheCentresInsideInAnyCornerOrder) {
    const Frame f = sheet();
    // Pixels x 12..38, y 60..78: columns i = 1, 2, 3 (x 15, 25, 35), rows j = 2, 3 (y 75, 65).
    const std::vector<std::int64_t> want{id(1, 2), id(2, 2), id(3, 2),
                                         id(1, 3), id(2, 3), id(3, 3)};
    EXPECT_EQ(idsOfRows(f, rowsInRectangle(topView(), f.x, f.y, f.z, {}, {12, 60}, {38, 78})),
              want);
    EXPECT_EQ(idsOfRows(f, rowsInRectangle(topView(), f.x, f.y, f.z, {}, {38, 60}, {12, 78})),
              want);
    // A tiny rectangle around one centre takes that sphere alone.
    EXPECT_EQ(
        idsOfRows(f, rowsInRectangle(topView(), f.x, f.y, f.z, {}, {44.9, 54.9}, {45.1, 55.1})),
        (std::vector<std::int64_t>{id(4, 4)}));
    EXPECT_TRUE(rowsInRectangle(topView(), f.x, f.y, f.z, {}, {0, 0}, {4, 4}).empty());
}

TEST(ScreenSelection, HiddenRowsAreNeverSelected) {
    const Frame f = sheet();
    std::vector<std::uint8_t> mask(f.size(), 1);
    mask[f.rowOf(id(2, 2)).value()] = 0;
    EXPECT_EQ(idsOfRows(f, rowsInRectangle(topView(), f.x, f.y, f.z, mask, {20, 60}, {30, 80})),
              (std::vector<std::int64_t>{id(2, 3)}));
}

TEST(ScreenSelection, TriangleLassoIsExact) {
    const Frame f = sheet();
    // Right triangle (0,100) (52,100) (0,48): centres with x + (100 - y) < 52, that is
    // 10 (i + j) + 10 < 52: i + j <= 4.
    const std::vector<glm::dvec2> lasso{{0, 100}, {52, 100}, {0, 48}};
    std::vector<std::int64_t> want;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i)
            if (i + j <= 4)
                want.push_back(id(i, j));
    EXPECT_EQ(idsOfRows(f, rowsInPolygon(topView(), f.x, f.y, f.z, {}, lasso)), want);
}

TEST(ScreenSelection, ConcaveLassoLeavesItsNotchOut) {
    const Frame f = sheet();
    // An L: the left column and the bottom row (j = 0), drawn clockwise on screen.
    const std::vector<glm::dvec2> lasso{{0, 0}, {10, 0}, {10, 90}, {50, 90}, {50, 100}, {0, 100}};
    const std::vector<std::int64_t> want{id(0, 0), id(1, 0), id(2, 0), id(3, 0), id(4, 0),
                                         id(0, 1), id(0, 2), id(0, 3), id(0, 4)};
    EXPECT_EQ(idsOfRows(f, rowsInPolygon(topView(), f.x, f.y, f.z, {}, lasso)), want);
}

TEST(ScreenSelection, SelfCrossingLassoAlternatesInAndOut) {
    // A bow tie: its edges cross at (52, 50), making a left and a right lobe (shifted by 2 px
    // so that no centre lies on an edge).
    const std::vector<glm::dvec2> bowTie{{2, 0}, {102, 100}, {102, 0}, {2, 100}};
    EXPECT_TRUE(insidePolygon({10, 50}, bowTie));
    EXPECT_TRUE(insidePolygon({90, 50}, bowTie));
    EXPECT_FALSE(insidePolygon({52, 10}, bowTie));
    EXPECT_FALSE(insidePolygon({52, 90}, bowTie));
    const Frame f = sheet();
    // Left lobe: x - 2 < y and x - 2 < 100 - y; right lobe: both >.
    std::vector<std::int64_t> want;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const double px = 10 * i + 5 - 2, py = 95 - 10 * j;
            if ((px < py && px < 100 - py) || (px > py && px > 100 - py))
                want.push_back(id(i, j));
        }
    EXPECT_EQ(want.size(), 15u);
    EXPECT_EQ(idsOfRows(f, rowsInPolygon(topView(), f.x, f.y, f.z, {}, bowTie)), want);
}

TEST(ScreenSelection, DegenerateLassosSelectNothing) {
    const Frame f = sheet();
    const std::vector<glm::dvec2> line{{0, 0}, {100, 100}};
    EXPECT_TRUE(rowsInPolygon(topView(), f.x, f.y, f.z, {}, line).empty());
    EXPECT_TRUE(rowsInPolygon(topView(), f.x, f.y, f.z, {}, {}).empty());
}

TEST(ScreenSelection, PerspectiveSkipsCentresBehindTheEye) {
    // Eye at z = 5 looking down on the sheet; a sphere above the eye is behind it and must not
    // be selected even though its mirrored projection would fall inside the rectangle.
    std::vector<Sphere> s{{1, 0, 0, 0}, {2, 0.5, 0, 0}, {3, 0, 0, 10}, {4, 3, 3, 0}};
    const Frame f = frameOf(s);
    const glm::dmat4 view =
        glm::lookAt(glm::dvec3(0, 0, 5), glm::dvec3(0, 0, 0), glm::dvec3(0, 1, 0));
    const ScreenMapping m{glm::perspective(glm::radians(60.0), 1.0, 0.1, 100.0) * view, {200, 200}};
    glm::dvec2 p;
    ASSERT_TRUE(projectToScreen(m, 0, 0, 0, p));
    EXPECT_NEAR(p.x, 100.0, 1e-9);
    EXPECT_NEAR(p.y, 100.0, 1e-9);
    EXPECT_EQ(idsOfRows(f, rowsInRectangle(m, f.x, f.y, f.z, {}, {90, 90}, {130, 110})),
              (std::vector<std::int64_t>{1, 2}));
}

// Issue 41, item 3: a rectangle takes the spheres in view, not the whole depth behind them. Three
// sheets stacked under each other, seen from above: the top one is all that shows, until the top
// sheet's corner is hidden; then the sheet under shows there. Perspective views too.
TEST(ScreenSelection, FrontmostRowsAreTheOnesInView) {
    std::vector<Sphere> s;
    for (int k = 0; k < 3; ++k) // sheets at z = 0 (top), -1, -2; ids 101.., 201.., 301..
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 5; ++i)
                s.push_back({101 + 100 * k + i + 5 * j, i + 0.5, j + 0.5, -1.0 * k});
    const Frame f = frameOf(s);
    // Orthographic, looking down -z from above (z = 0 nearest).
    const ScreenMapping top{glm::ortho(0.0, 10.0, 0.0, 10.0, -1.0, 5.0), {100.0, 100.0}};
    const auto all = rowsInRectangle(top, f.x, f.y, f.z, {}, {0, 0}, {100, 100});
    ASSERT_EQ(all.size(), 75u); // through the depth
    const auto seen = frontmostRows(top, f.x, f.y, f.z, f.radius, {}, all);
    ASSERT_EQ(seen.size(), 25u);
    for (std::uint32_t r : seen)
        EXPECT_LT(f.ids[r], 200);
    // Hide the top sheet's corner sphere (mask): the one under it shows there.
    std::vector<std::uint8_t> mask(f.size(), 1);
    mask[0] = 0;
    const auto partly = rowsInRectangle(top, f.x, f.y, f.z, mask, {0, 0}, {100, 100});
    const auto under = frontmostRows(top, f.x, f.y, f.z, f.radius, mask, partly);
    EXPECT_EQ(under.size(), 25u);
    EXPECT_NE(std::find(under.begin(), under.end(), 25u), under.end()); // id 201, row 25
    // A perspective camera above the sheets.
    const ScreenMapping eye{
        glm::perspective(glm::radians(60.0), 1.0, 0.5, 50.0) *
            glm::lookAt(glm::dvec3(2.5, 2.5, 8.0), glm::dvec3(2.5, 2.5, 0.0), glm::dvec3(0, 1, 0)),
        {200.0, 200.0}};
    const auto inEye = rowsInRectangle(eye, f.x, f.y, f.z, {}, {0, 0}, {200, 200});
    const auto front = frontmostRows(eye, f.x, f.y, f.z, f.radius, {}, inEye);
    std::size_t topSheet = 0;
    for (std::uint32_t r : front)
        topSheet += f.ids[r] < 200 ? 1 : 0;
    EXPECT_EQ(topSheet, 25u); // (lower spheres peek through the gaps between touching ones)
}
