// Autosave and crash recovery: the session is written every 60 s (when it changed) and on exit
// to a recovery file in the user's state folder; a marker says whether the exit was clean, so
// after a crash the next start can offer the recovered session.
#pragma once

#include "core/session/session.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace faultline::core {

// $XDG_STATE_HOME/faultline, or ~/.local/state/faultline.
std::string defaultStateFolder();

struct PendingRecovery {
    std::string sessionPath;
    std::string savedAt; // ISO 8601, UTC
};

class Autosave {
  public:
    static constexpr std::chrono::seconds kInterval{60};

    explicit Autosave(std::string folder = defaultStateFolder());

    // Call often (every UI frame): saves when the interval has passed and the session changed.
    // Returns true when it saved. Never throws: a failed save is reported by lastError().
    bool tick(const Session& session, std::chrono::steady_clock::time_point now);
    // Saves now; `cleanExit` marks a normal shutdown (nothing to offer at the next start).
    bool saveNow(const Session& session, bool cleanExit);
    // A recovery left by a session that did not exit cleanly, if any.
    std::optional<PendingRecovery> pending() const;
    // Marks the recovery as dealt with (recovered or declined).
    void discard();

    const std::string& folder() const { return m_folder; }
    std::string sessionPath() const;
    const std::string& lastError() const { return m_lastError; }

  private:
    std::string m_folder;
    std::uint64_t m_savedVersion = 0;
    std::chrono::steady_clock::time_point m_lastSave{};
    std::string m_lastError;
};

} // namespace faultline::core
