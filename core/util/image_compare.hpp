// Comparing two RGBA8 images of the same size, as image tests and the journal's `expect image`
// judge a render against its reference: the mean absolute difference over every byte, the
// pixels that differ by more than a threshold in some channel (a missing small feature shows
// there), and the structural similarity (SSIM) of their luma, which follows what a reader sees
// (edges, shading, structure) rather than bytes, and ignores a uniform offset of a few levels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace faultline::core {

struct ImageView {
    int width = 0;
    int height = 0;
    const std::uint8_t* rgba = nullptr; // width * height * 4, rows top first
};

struct ImageComparison {
    bool sameSize = false;
    double meanAbsDiff = 0;    // 0..255 over every channel of every pixel
    std::size_t differing = 0; // pixels whose largest channel difference exceeds the threshold
    double ssim = 1;           // mean SSIM over 8x8 windows of the luma (stride 4), -1..1
};

// Differences of `a` against `b`. Different sizes: sameSize false, meanAbsDiff infinity,
// differing = a's pixel count, ssim 0.
ImageComparison compareImages(const ImageView& a, const ImageView& b, int threshold = 48);

// Mean SSIM (Wang et al. 2004: C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 255) over 8x8 windows of
// the luma (Rec. 601 weights), windows every 4 pixels; images smaller than a window are one
// window. Alpha is ignored. Same sizes only (0 otherwise).
double structuralSimilarity(const ImageView& a, const ImageView& b);

// The journal's expectation: nullopt when `a` passes against `b`, else what failed, e.g.
// "expected SSIM >= 0.95, actual 0.81".
std::optional<std::string> imageMismatch(const ImageView& a, const ImageView& b, double maxMeanDiff,
                                         std::optional<long long> maxDifferingPixels,
                                         double minSsim);

} // namespace faultline::core
