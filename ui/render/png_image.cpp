#include "ui/render/png_image.hpp"

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

double meanAbsDiff(const RgbaImage& a, const RgbaImage& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        return std::numeric_limits<double>::infinity();
    if (a.pixels.empty())
        return 0.0;
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        sum += static_cast<std::uint64_t>(std::abs(int(a.pixels[i]) - int(b.pixels[i])));
    return double(sum) / double(a.pixels.size());
}

std::size_t differingPixels(const RgbaImage& a, const RgbaImage& b, int threshold) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        return a.pixels.size() / 4;
    std::size_t count = 0;
    for (std::size_t i = 0; i + 3 < a.pixels.size(); i += 4) {
        int worst = 0;
        for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])));
        count += worst > threshold;
    }
    return count;
}

} // namespace faultline::ui
