// RGBA8 images as the renderer hands them out, PNG files (stb_image_write / stb_image), and the
// comparisons (core/util/image_compare.hpp) used by image tests and the journal's `expect image`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace faultline::ui {

struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels; // width * height * 4, top row first, straight alpha

    bool empty() const { return width <= 0 || height <= 0; }
    const std::uint8_t* at(int x, int y) const {
        return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
    }
};

// Throws std::runtime_error naming the path when the file cannot be written.
void writePng(const RgbaImage& image, const std::string& path);
// Throws std::runtime_error naming the path when the file is missing or not an image.
RgbaImage readPng(const std::string& path);

// Mean of |a - b| over every channel of every pixel (0..255); infinity when sizes differ.
double meanAbsDiff(const RgbaImage& a, const RgbaImage& b);
// Pixels whose largest channel difference exceeds `threshold`: a small feature that is missing
// (a box handle, a thin edge) shows here even where the mean over all bytes hardly moves. The
// pixel count of `a` when sizes differ.
std::size_t differingPixels(const RgbaImage& a, const RgbaImage& b, int threshold = 48);
// Mean SSIM of the two images' luma (core/util/image_compare.hpp); 0 when sizes differ.
double structuralSimilarity(const RgbaImage& a, const RgbaImage& b);

} // namespace faultline::ui
