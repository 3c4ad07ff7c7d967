// The journal a session records: every command applied, in order, as given. An action the
// caller carries out in the background (an export) keeps its place from the moment it is asked
// for: lines recorded after it wait until it is settled, so a replay runs it on the state it
// read, not on what the user changed while it ran. Owned by Session (issue 39: the journal
// and the op registry were Session's own members among fifty others).
#pragma once

#include "core/session/command_args.hpp"

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

namespace faultline::core {

class JournalRecorder {
  public:
    using Sink = std::function<void(const Json&)>;

    const std::vector<Json>& lines() const { return m_lines; }
    // `sink` receives each line as it is recorded in its place; `held`, each line the moment it
    // is recorded behind an unsettled action (the GUI writes it as a comment, so a crash during
    // a long export loses none of the user's commands).
    void setSinks(Sink sink, Sink held) {
        m_sink = std::move(sink);
        m_held = std::move(held);
    }

    // A command applied: recorded now, or behind the oldest open place.
    void record(const Json& cmd);
    // A place for an action asked for now.
    std::uint64_t reserve();
    // The action at `place` worked: `cmd` takes its place.
    void settle(std::uint64_t place, const Json& cmd);
    // It failed or was cancelled: the place records nothing.
    void drop(std::uint64_t place);
    // Every open place given up (shutdown), so the lines waiting behind them are written.
    void dropPending();
    std::size_t pending() const;

  private:
    void flush(); // the lines no open place holds back
    std::vector<Json> m_lines;
    Sink m_sink, m_held;
    struct Line {
        std::uint64_t place = 0; // a reserved action's place; 0: a line recorded behind one
        bool settled = false;
        std::optional<Json> cmd;
    };
    std::deque<Line> m_waiting; // from the oldest open place on
    std::uint64_t m_nextPlace = 1;
};

} // namespace faultline::core
