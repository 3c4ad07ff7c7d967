// Figures of a session: one view (its frame binding, colouring, camera, boxes, the session's
// visibility) rendered offscreen to a PNG. Behind the journal's "render" op and `faultline render`.
#pragma once

#include "core/color/colormap.hpp"
#include "core/data/frame_prefetcher.hpp"
#include "core/session/session.hpp"
#include "ui/render/movie_writer.hpp"
#include "ui/render/png_image.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

struct FigureRequest {
    std::string view = "main";
    std::string path;
    int width = 1280;
    int height = 720;
    bool transparent = false;
    std::optional<std::size_t> frame; // overrides the view's frame binding
    // For frame sequences: one colour range and camera for every frame (else the view's).
    std::optional<core::ValueRange> colorRange;
    std::optional<core::CameraState> camera;
    std::string caption; // top-left label
};

// The figure as an image. `frame`, when given, is the request's frame already loaded.
// Throws core::CommandError with the reason (no such view, no data, no OpenGL).
RgbaImage renderSessionImage(core::Session& session, const FigureRequest& request,
                             std::shared_ptr<const core::Frame> frame = nullptr);
// ... written to request.path as a PNG.
void renderSessionFigure(core::Session& session, const FigureRequest& request);

// A view over a range of frames: an H.264 MP4 (path ending .mp4, one video frame per data
// frame, the timestep in the top-left corner) or a PNG sequence (a path with a printf-style
// frame number, %d or %04d, filled with the data frame's number). The colour range (when the
// view's is not fixed) spans every frame of the data and the camera (when the view's was never
// placed) fits the first and last frame, so frames match however the run is split. Frames
// load ahead through a FramePrefetcher. Made on the thread that renders (GL).
struct SequenceRequest {
    FigureRequest figure; // path: the movie or the pattern
    std::size_t first = 0, last = 0, step = 1;
    int framesPerSecond = 10;
};

class FrameSequence {
  public:
    // Checks the request (view, data, frames, path) and opens the movie; CommandError else.
    // Only frames the session's frame selection holds are rendered (replay --frames/--shard).
    FrameSequence(core::Session& session, SequenceRequest request);
    ~FrameSequence(); // unfinished: a movie is closed as far as it got
    FrameSequence(const FrameSequence&) = delete;
    FrameSequence& operator=(const FrameSequence&) = delete;

    // Renders the next frame when it is loaded (wait: block until it is); false when nothing is
    // left to do. CommandError when a frame cannot be loaded or written.
    bool step(bool wait = true);
    void finish(); // every frame, then the movie's index
    std::size_t done() const { return m_next; }
    std::size_t total() const { return m_frames.size(); }
    bool finished() const { return m_finished; }
    const std::string& path() const { return m_request.figure.path; }
    // The data frames it renders, in order.
    const std::vector<std::size_t>& frames() const { return m_frames; }
    // The colour range every frame is drawn with (none: the view's own per frame).
    const std::optional<core::ValueRange>& colorRange() const {
        return m_request.figure.colorRange;
    }

  private:
    core::Session& m_session;
    SequenceRequest m_request;
    std::vector<std::size_t> m_frames;
    std::size_t m_next = 0;
    bool m_finished = false;
    std::unique_ptr<core::FramePrefetcher> m_prefetcher;
    std::unique_ptr<MovieWriter> m_movie;
};

// A path names a PNG sequence when it holds one printf integer conversion (%d, %04d, ...).
bool isFrameSequencePattern(const std::string& path);
// The pattern with the frame number filled in.
std::string framePath(const std::string& pattern, std::size_t frame);

// Adds {"op":"render","view":..,"path":..,"size":[w,h],"transparent":..,"frame":..} and the
// frame range form {"frames":[first,last],"step":n,"fps":n} to a session.
void registerRenderOp(core::Session& session);

} // namespace faultline::ui
