// The image comparison of image tests and `expect image` (issue 39): SSIM by hand on small
// cases, and what the byte mean misses that SSIM sees.
#include "core/util/image_compare.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace faultline::core;

namespace {

struct Image {
    int w, h;
    std::vector<std::uint8_t> px;
    Image(int w_, int h_, std::uint8_t grey = 0)
        : w(w_), h(h_), px(std::size_t(w_) * h_ * 4, grey) {
        for (std::size_t i = 3; i < px.size(); i += 4)
            px[i] = 255;
    }
    void set(int x, int y, std::uint8_t grey) {
        std::uint8_t* p = &px[(std::size_t(y) * w + x) * 4];
        p[0] = p[1] = p[2] = grey;
    }
    ImageView view() const { return {w, h, px.data()}; }
};

} // namespace

TEST(ImageCompare, IdenticalImagesScoreOne) {
    Image a(32, 24);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x)
            a.set(x, y, std::uint8_t((x * 7 + y * 13) % 256));
    const ImageComparison c = compareImages(a.view(), a.view());
    EXPECT_TRUE(c.sameSize);
    EXPECT_EQ(c.meanAbsDiff, 0.0);
    EXPECT_EQ(c.differing, 0u);
    EXPECT_DOUBLE_EQ(c.ssim, 1.0);
}

// One 8x8 window (the image is the window): flat grey 100 against flat grey 120 has no variance,
// so SSIM is the luminance term alone, (2 * 100 * 120 + C1) / (100^2 + 120^2 + C1).
TEST(ImageCompare, OneWindowByHand) {
    Image a(8, 8, 100), b(8, 8, 120);
    const double c1 = (0.01 * 255) * (0.01 * 255);
    const double expected = (2.0 * 100 * 120 + c1) / (100.0 * 100 + 120.0 * 120 + c1);
    EXPECT_NEAR(structuralSimilarity(a.view(), b.view()), expected, 1e-4);
    // Half the window 0 and half 200 against its inverse: means equal (100), variances equal
    // (100^2), covariance -100^2: SSIM = (-2 * 100^2 + C2) / (2 * 100^2 + C2).
    Image c(8, 8), d(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            c.set(x, y, x < 4 ? 0 : 200);
            d.set(x, y, x < 4 ? 200 : 0);
        }
    const double c2 = (0.03 * 255) * (0.03 * 255);
    EXPECT_NEAR(structuralSimilarity(c.view(), d.view()), (-2e4 + c2) / (2e4 + c2), 1e-3);
}

// Small dots (one pixel in every 8x8 block, 60 levels over the background, like far glyphs)
// each moved by one pixel: the byte mean hardly moves (a render test at max_mean_abs_diff 2
// passes it), SSIM falls far below the journal's default.
TEST(ImageCompare, MovedDotsFailSsimWhereTheMeanPasses) {
    Image a(128, 128, 128), b(128, 128, 128);
    for (int y = 3; y < 128; y += 8)
        for (int x = 3; x < 128; x += 8) {
            a.set(x, y, 188);
            b.set(x + 1, y, 188);
        }
    const ImageComparison c = compareImages(a.view(), b.view());
    EXPECT_LT(c.meanAbsDiff, 2.0);
    EXPECT_LT(c.ssim, 0.7);
    const auto why = imageMismatch(a.view(), b.view(), 2.0, std::nullopt, 0.95);
    ASSERT_TRUE(why.has_value());
    EXPECT_NE(why->find("SSIM"), std::string::npos) << *why;
    // The same dots 2 levels brighter everywhere: no change of structure.
    Image e(128, 128, 130);
    for (int y = 3; y < 128; y += 8)
        for (int x = 3; x < 128; x += 8)
            e.set(x, y, 190);
    EXPECT_GT(structuralSimilarity(a.view(), e.view()), 0.99);
    EXPECT_FALSE(imageMismatch(a.view(), e.view(), 2.0, std::nullopt, 0.95).has_value());
}

TEST(ImageCompare, DifferentSizesAreNoMatch) {
    Image a(8, 8), b(9, 8);
    const ImageComparison c = compareImages(a.view(), b.view());
    EXPECT_FALSE(c.sameSize);
    EXPECT_TRUE(std::isinf(c.meanAbsDiff));
    EXPECT_EQ(c.differing, 64u);
    EXPECT_EQ(c.ssim, 0.0);
    EXPECT_EQ(*imageMismatch(a.view(), b.view(), 2, std::nullopt, 0.95),
              "expected size 9x8, actual 8x8");
}
