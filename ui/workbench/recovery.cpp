#include "ui/workbench/recovery.hpp"

#include "core/session/session.hpp"

namespace faultline::ui {

Recovery::Recovery(const std::string& stateDir) {
    if (stateDir.empty())
        return;
    m_autosaver.emplace(stateDir);
    m_pending = m_autosaver->pending(); // a crashed run's session, offered at start
}

std::optional<std::string> Recovery::recover() {
    if (!m_pending)
        return std::nullopt;
    std::string path = m_pending->sessionPath;
    m_pending.reset();
    m_recovering = true;
    m_autosaver->discard();
    return path;
}

void Recovery::discard() {
    if (!m_pending)
        return;
    m_pending.reset();
    m_autosaver->discard();
}

std::optional<std::string> Recovery::autosave(const core::Session& session, double now,
                                              double interval) {
    // Until the user decided about a recovery, its file stays as it is.
    if (!m_autosaver || m_pending || m_recovering)
        return std::nullopt;
    if (now - m_lastTry < interval)
        return std::nullopt;
    m_lastTry = now;
    if (session.version() == m_savedVersion)
        return std::nullopt;
    if (m_autosaver->saveNow(session, false)) { // not a clean exit until exitCleanly says so
        m_savedVersion = session.version();
        return std::nullopt;
    }
    m_lastTry = now + 300; // do not repeat the message every frame
    return "Autosave failed: " + m_autosaver->lastError();
}

void Recovery::exitCleanly(const core::Session& session) {
    if (m_autosaver && !m_pending && !m_recovering)
        m_autosaver->saveNow(session, true);
}

} // namespace faultline::ui
