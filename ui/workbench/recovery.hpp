// Autosave and crash recovery for the workbench: the session saved every so often into the
// state folder, a clean exit saying so, and at start the session a crashed run left, offered
// once (recover or discard). Until the user decided, and while a recovered session is opening,
// autosave leaves that file alone. One of the Workbench's parts with one job each (issue 39).
#pragma once

#include "core/session/autosave.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace faultline::core {
class Session;
}

namespace faultline::ui {

class Recovery {
  public:
    // An empty folder: no autosave, nothing to recover.
    explicit Recovery(const std::string& stateDir);

    // The session a crashed run left, until the user decides.
    const std::optional<core::PendingRecovery>& pending() const { return m_pending; }
    // "Recover it": the session file to open; autosave waits until opened() or abandoned().
    std::optional<std::string> recover();
    // "Discard": the crashed run's session is forgotten.
    void discard();
    // A recovered session is being opened (its file must stay until it has).
    bool recovering() const { return m_recovering; }
    void opened() { m_recovering = false; }
    void abandoned() { m_recovering = false; } // it failed to open, or was left closed

    // Saves `session` when `interval` seconds passed since the last try and it changed since;
    // an error message when the save failed (said once in five minutes).
    std::optional<std::string> autosave(const core::Session& session, double now, double interval);
    // The workbench closes normally: nothing to offer next time.
    void exitCleanly(const core::Session& session);

  private:
    std::optional<core::Autosave> m_autosaver;
    std::optional<core::PendingRecovery> m_pending;
    bool m_recovering = false;
    double m_lastTry = 0.0;
    std::uint64_t m_savedVersion = 0;
};

} // namespace faultline::ui
