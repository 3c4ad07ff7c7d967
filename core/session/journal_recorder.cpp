#include "core/session/journal_recorder.hpp"

#include <algorithm>

namespace faultline::core {

void JournalRecorder::record(const Json& cmd) {
    if (!m_waiting.empty()) {
        m_waiting.push_back({0, true, cmd});
        if (m_held)
            m_held(cmd);
        return;
    }
    m_lines.push_back(cmd);
    if (m_sink)
        m_sink(cmd);
}

void JournalRecorder::flush() {
    while (!m_waiting.empty() && m_waiting.front().settled) {
        std::optional<Json> cmd = std::move(m_waiting.front().cmd);
        m_waiting.pop_front();
        if (cmd) {
            m_lines.push_back(*cmd);
            if (m_sink)
                m_sink(*cmd);
        }
    }
}

std::uint64_t JournalRecorder::reserve() {
    m_waiting.push_back({m_nextPlace, false, std::nullopt});
    return m_nextPlace++;
}

void JournalRecorder::settle(std::uint64_t place, const Json& cmd) {
    for (auto& line : m_waiting)
        if (line.place == place && !line.settled) {
            line.settled = true;
            line.cmd = cmd;
            break;
        }
    flush();
}

void JournalRecorder::drop(std::uint64_t place) {
    for (auto& line : m_waiting)
        if (line.place == place)
            line.settled = true;
    flush();
}

void JournalRecorder::dropPending() {
    for (auto& line : m_waiting)
        line.settled = true;
    flush();
}

std::size_t JournalRecorder::pending() const {
    return static_cast<std::size_t>(
        std::count_if(m_waiting.begin(), m_waiting.end(),
                      [](const Line& l) { return l.place != 0 && !l.settled; }));
}

} // namespace faultline::core
