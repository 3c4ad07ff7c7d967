#include "ui/render/png_image.hpp"

#include "core/util/image_compare.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace faultline::ui {

void writePng(const RgbaImage& image, const std::string& path) {
    if (image.empty() || image.pixels.size() != std::size_t(image.width) * image.height * 4)
        throw std::runtime_error("cannot write " + path + ": empty or malformed image");
    if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.pixels.data(),
                        image.width * 4))
        throw std::runtime_error("cannot write " + path);
}

RgbaImage readPng(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error("cannot read image " + path + ": " + (why ? why : "unknown"));
    }
    RgbaImage image{w, h, std::vector<std::uint8_t>(data, data + std::size_t(w) * h * 4)};
    stbi_image_free(data);
    return image;
}

namespace {
// An image whose pixels do not fill width x height compares as no size at all.
core::ImageView view(const RgbaImage& im) {
    if (im.width < 0 || im.height < 0 ||
        im.pixels.size() != std::size_t(im.width) * std::size_t(im.height) * 4)
        return {-1, -1, nullptr};
    return {im.width, im.height, im.pixels.data()};
}
} // namespace

double meanAbsDiff(const RgbaImage& a, const RgbaImage& b) {
    return core::compareImages(view(a), view(b)).meanAbsDiff;
}

std::size_t differingPixels(const RgbaImage& a, const RgbaImage& b, int threshold) {
    return core::compareImages(view(a), view(b), threshold).differing;
}

double structuralSimilarity(const RgbaImage& a, const RgbaImage& b) {
    return core::structuralSimilarity(view(a), view(b));
}

} // namespace faultline::ui
