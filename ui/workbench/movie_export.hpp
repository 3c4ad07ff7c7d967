// A movie being written from the UI loop: the journal's render with "frames" (a FrameSequence),
// one data frame per step so the window stays live (frames load ahead on the prefetcher's
// threads; rendering needs the window's OpenGL context, so it stays on the UI thread). Its
// journal place is held from the moment it is asked for and settled with its command once the
// movie is written (dropped when it fails or is cancelled). One of the Workbench's parts with
// one job each (issue 39); the Workbench draws its options and progress.
#pragma once

#include "core/session/command_args.hpp"
#include "core/session/journal_place.hpp"
#include "ui/viewport/session_figure.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

namespace faultline::core {
class Session;
}

namespace faultline::ui {

class MovieExport {
  public:
    explicit MovieExport(core::Session& session) : m_session(session) {}
    ~MovieExport();
    MovieExport(const MovieExport&) = delete;
    MovieExport& operator=(const MovieExport&) = delete;

    bool running() const { return m_sequence != nullptr; }
    // Starts writing `request`; `command` is the render the journal records once it is written.
    // Throws (CommandError, std::exception) when it cannot start; nothing is running then.
    void start(const SequenceRequest& request, core::Json command);
    std::pair<std::size_t, std::size_t> progress() const; // frames done, of total
    const std::string& path() const;                      // while running

    // Renders the next frame when it is loaded. Running while frames remain; Written (with
    // what to tell the user) once the movie is whole and journalled; Failed with why.
    enum class State { Idle, Running, Written, Failed };
    struct Step {
        State state = State::Idle;
        std::string message;
    };
    Step step();
    // Stops: an MP4 is closed as far as it got. What to tell the user; empty when none ran.
    std::string cancel();

  private:
    void stop();
    core::Session& m_session;
    std::unique_ptr<FrameSequence> m_sequence;
    core::Json m_command;
    std::unique_ptr<core::JournalPlace> m_place; // its journal place while running
};

} // namespace faultline::ui
