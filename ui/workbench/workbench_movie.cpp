// File > Export > Movie: the journal's render with "frames" driven from the UI loop, one data
// frame per UI frame so the window stays live (frames load ahead on the prefetcher's threads;
// rendering needs the window's OpenGL context, so it stays on this thread), with progress and
// Cancel. Journalled, like the background exports, once the movie is written.
#include "ui/workbench/workbench.hpp"

#include "core/session/commands.hpp"
#include <imgui.h>

#include <filesystem>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

namespace {

// A PNG path becomes a pattern (name_%04d.png) unless it is one already.
std::string framePattern(const std::string& path) {
    if (isFrameSequencePattern(path))
        return path;
    fs::path p(path);
    const std::string stem = p.extension() == ".png" ? p.stem().string() : p.filename().string();
    return (p.parent_path() / (stem + "_%04d.png")).string();
}

} // namespace

void Workbench::showMovieOptions() {
    const auto ds = m_session.dataset();
    if (!ds) {
        error("Open data first: a movie shows the main view over its frames");
        return;
    }
    const int last = static_cast<int>(ds->frameCount()) - 1;
    movieOptions.first = std::clamp(movieOptions.first, 0, last);
    movieOptions.last =
        movieOptions.last <= 0 || movieOptions.last > last ? last : movieOptions.last;
    m_showMovieOptions = true;
}

void Workbench::exportMovie(const std::string& pathIn) {
    if (m_movie.running()) {
        error("A movie is being written already");
        return;
    }
    const MovieOptions& o = movieOptions;
    std::string path = fs::absolute(pathIn).string();
    if (o.pngFrames)
        path = framePattern(path);
    else if (fs::path(path).extension() != ".mp4")
        path += ".mp4";
    core::cmd::Render cmd("main", path, o.width, o.height);
    cmd.frames(o.first, o.last);
    if (o.step > 1)
        cmd.step(o.step);
    if (!o.pngFrames && o.fps != 10)
        cmd.fps(o.fps);
    SequenceRequest request;
    request.figure.view = "main";
    request.figure.path = path;
    request.figure.width = o.width;
    request.figure.height = o.height;
    request.first = static_cast<std::size_t>(std::max(0, o.first));
    request.last = static_cast<std::size_t>(std::max(0, o.last));
    request.step = static_cast<std::size_t>(std::max(1, o.step));
    request.framesPerSecond = o.fps;
    try {
        m_movie.start(request, cmd);
    } catch (const std::exception& e) {
        error(std::string("Movie: ") + e.what());
        return;
    }
    info("Writing " + fs::path(path).filename().string() + ": " +
         std::to_string(m_movie.progress().second) + " frames");
}

void Workbench::cancelMovie() {
    if (const std::string said = m_movie.cancel(); !said.empty())
        info(said);
}

void Workbench::drawMovie() {
    const ImGuiIO& io = ImGui::GetIO();
    switch (const MovieExport::Step step = m_movie.step(); step.state) {
    case MovieExport::State::Written:
        info(step.message);
        break;
    case MovieExport::State::Failed:
        error("Movie: " + step.message);
        break;
    default:
        break;
    }
    if (m_movie.running()) {
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                                ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        if (ImGui::Begin("Writing the movie", nullptr,
                         ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                             ImGuiWindowFlags_NoCollapse)) {
            const auto [done, total] = movieProgress();
            ImGui::TextUnformatted(fs::path(m_movie.path()).filename().string().c_str());
            char label[64];
            std::snprintf(label, sizeof label, "frame %zu of %zu", done, total);
            ImGui::ProgressBar(total ? float(done) / float(total) : 0.0f, ImVec2(320 * m_scale, 0),
                               label);
            if (ImGui::Button("Cancel"))
                cancelMovie();
            m_items.markLastItem("movie.cancel");
        }
        ImGui::End();
        return;
    }
    if (!m_showMovieOptions)
        return;
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Export movie", &m_showMovieOptions,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                         ImGuiWindowFlags_NoCollapse)) {
        const auto ds = m_session.dataset();
        const int last = ds ? static_cast<int>(ds->frameCount()) - 1 : 0;
        MovieOptions& o = movieOptions;
        ImGui::TextUnformatted("The main view as it is now, over a range of frames.");
        ImGui::PushItemWidth(90 * m_scale);
        ImGui::InputInt("First frame", &o.first);
        ImGui::SameLine();
        ImGui::InputInt("Last frame", &o.last);
        ImGui::InputInt("Every n-th", &o.step);
        ImGui::InputInt("Width", &o.width, 0);
        ImGui::SameLine();
        ImGui::InputInt("Height", &o.height, 0);
        ImGui::PopItemWidth();
        o.first = std::clamp(o.first, 0, last);
        o.last = std::clamp(o.last, o.first, last);
        o.step = std::clamp(o.step, 1, std::max(1, last + 1));
        o.width = std::clamp(o.width, 16, 7680);
        o.height = std::clamp(o.height, 16, 4320);
        int kind = o.pngFrames ? 1 : 0;
        ImGui::RadioButton("MP4 movie (H.264)", &kind, 0);
        ImGui::SameLine();
        ImGui::RadioButton("A PNG per frame", &kind, 1);
        o.pngFrames = kind == 1;
        if (!o.pngFrames) {
            ImGui::PushItemWidth(90 * m_scale);
            ImGui::InputInt("Frames per second", &o.fps);
            ImGui::PopItemWidth();
            o.fps = std::clamp(o.fps, 1, 120);
        }
        const std::size_t count = std::size_t((o.last - o.first) / o.step + 1);
        ImGui::TextDisabled("%zu frames at %d x %d", count, o.width, o.height);
        if (ImGui::Button("Save as...")) {
            m_showMovieOptions = false;
            const std::string folder = exportFolder(); // where the last export went
            if (o.pngFrames)
                m_dialog.open("Save a PNG per frame (name_0000.png, ...)", FileDialog::Mode::Save,
                              "export-movie", {".png"}, folder, "frame.png");
            else
                m_dialog.open("Save the movie", FileDialog::Mode::Save, "export-movie", {".mp4"},
                              folder, "faultline-movie.mp4");
        }
        m_items.markLastItem("movie.save");
        ImGui::SameLine();
        if (ImGui::Button("Cancel"))
            m_showMovieOptions = false;
    }
    ImGui::End();
}

} // namespace faultline::ui
