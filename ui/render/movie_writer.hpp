// MovieWriter: images into an H.264 MP4 through libavcodec/libavformat (libx264, yuv420p, the
// pixel format every player reads). One image per video frame at a fixed rate.
#pragma once

#include "ui/render/png_image.hpp"

#include <memory>
#include <string>

namespace faultline::ui {

struct MovieSettings {
    int width = 1280; // even sizes: yuv420p halves the chroma planes (odd ones are rounded up)
    int height = 720;
    int framesPerSecond = 10;
    int quality = 20; // x264's constant rate factor: 0 lossless .. 51 worst; ~18 looks lossless
};

class MovieWriter {
  public:
    // Opens `path` for writing; std::runtime_error naming the path and libav's reason.
    MovieWriter(const std::string& path, const MovieSettings& settings);
    ~MovieWriter(); // without finish(): the file is closed as it is (a partial movie)
    MovieWriter(const MovieWriter&) = delete;
    MovieWriter& operator=(const MovieWriter&) = delete;

    // The image must be settings' size (RGBA, top row first).
    void add(const RgbaImage& image);
    // Flushes the encoder and writes the MP4 index. Idempotent.
    void finish();
    std::size_t framesWritten() const;

  private:
    struct State;
    std::unique_ptr<State> m_state;
};

// Frames and size of a video file as libavformat reads it back (for tests and `info`):
// counted by decoding every packet's frame. std::runtime_error when it cannot be read.
struct MovieProbe {
    std::size_t frames = 0;
    int width = 0, height = 0;
    std::string codec;
};
MovieProbe probeMovie(const std::string& path);

} // namespace faultline::ui
