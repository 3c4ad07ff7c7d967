#include "core/util/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

namespace faultline::core {

namespace {

std::vector<float> luma(const ImageView& im) {
    std::vector<float> out(std::size_t(im.width) * std::size_t(im.height));
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::uint8_t* p = im.rgba + 4 * i;
        out[i] = 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2];
    }
    return out;
}

// Window origins along an axis of `size` pixels: every `stride`, the last one flush with the end.
std::vector<int> windowStarts(int size, int window, int stride) {
    std::vector<int> out;
    if (size <= window)
        return {0};
    for (int s = 0; s + window <= size; s += stride)
        out.push_back(s);
    if (out.back() + window < size)
        out.push_back(size - window);
    return out;
}

} // namespace

double structuralSimilarity(const ImageView& a, const ImageView& b) {
    if (a.width != b.width || a.height != b.height || a.width <= 0 || a.height <= 0)
        return 0;
    constexpr int kWindow = 8, kStride = 4;
    constexpr double kC1 = (0.01 * 255) * (0.01 * 255), kC2 = (0.03 * 255) * (0.03 * 255);
    const std::vector<float> la = luma(a), lb = luma(b);
    const int ww = std::min(kWindow, a.width), wh = std::min(kWindow, a.height);
    double total = 0;
    std::size_t windows = 0;
    for (int y0 : windowStarts(a.height, kWindow, kStride))
        for (int x0 : windowStarts(a.width, kWindow, kStride)) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
            for (int y = y0; y < y0 + wh; ++y)
                for (int x = x0; x < x0 + ww; ++x) {
                    const std::size_t k = std::size_t(y) * std::size_t(a.width) + std::size_t(x);
                    const double p = la[k], q = lb[k];
                    sa += p;
                    sb += q;
                    saa += p * p;
                    sbb += q * q;
                    sab += p * q;
                }
            const double n = double(ww * wh);
            const double ma = sa / n, mb = sb / n;
            const double va = std::max(0.0, saa / n - ma * ma),
                         vb = std::max(0.0, sbb / n - mb * mb);
            const double cov = sab / n - ma * mb;
            total += ((2 * ma * mb + kC1) * (2 * cov + kC2)) /
                     ((ma * ma + mb * mb + kC1) * (va + vb + kC2));
            ++windows;
        }
    return total / double(windows);
}

ImageComparison compareImages(const ImageView& a, const ImageView& b, int threshold) {
    ImageComparison c;
    const std::size_t pixels =
        std::size_t(std::max(0, a.width)) * std::size_t(std::max(0, a.height));
    if (a.width != b.width || a.height != b.height) {
        c.meanAbsDiff = std::numeric_limits<double>::infinity();
        c.differing = pixels;
        c.ssim = 0;
        return c;
    }
    c.sameSize = true;
    if (pixels == 0)
        return c;
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (int ch = 0; ch < 4; ++ch) {
            const int d = std::abs(int(a.rgba[4 * i + ch]) - int(b.rgba[4 * i + ch]));
            sum += std::uint64_t(d);
            worst = std::max(worst, d);
        }
        c.differing += worst > threshold;
    }
    c.meanAbsDiff = double(sum) / double(4 * pixels);
    c.ssim = structuralSimilarity(a, b);
    return c;
}

std::optional<std::string> imageMismatch(const ImageView& a, const ImageView& b, double maxMeanDiff,
                                         std::optional<long long> maxDifferingPixels,
                                         double minSsim) {
    const ImageComparison c = compareImages(a, b);
    std::ostringstream msg;
    if (!c.sameSize)
        msg << "expected size " << b.width << "x" << b.height << ", actual " << a.width << "x"
            << a.height;
    else if (c.meanAbsDiff > maxMeanDiff)
        msg << "expected mean abs diff <= " << maxMeanDiff << ", actual " << c.meanAbsDiff;
    else if (maxDifferingPixels && (long long)c.differing > *maxDifferingPixels)
        msg << "expected at most " << *maxDifferingPixels
            << " pixels differing by more than 48, actual " << c.differing;
    else if (c.ssim < minSsim)
        msg << "expected SSIM >= " << minSsim << ", actual " << c.ssim;
    else
        return std::nullopt;
    return msg.str();
}

} // namespace faultline::core
