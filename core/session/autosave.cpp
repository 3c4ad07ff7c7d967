#include "core/session/autosave.hpp"

#include "core/io/byte_source.hpp"
#include "core/session/atomic_file.hpp"
#include "core/session/session_json.hpp"

#include <cstdlib>
#include <ctime>
#include <filesystem>

namespace faultline::core {

namespace fs = std::filesystem;

namespace {
std::string markerPath(const std::string& folder) {
    return (fs::path(folder) / "recovery.json").string();
}

std::string nowIso() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}
} // namespace

std::string defaultStateFolder() {
    if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg && *xdg)
        return (fs::path(xdg) / "faultline").string();
    const char* home = std::getenv("HOME");
    return (fs::path(home && *home ? home : "/tmp") / ".local" / "state" / "faultline").string();
}

Autosave::Autosave(std::string folder) : m_folder(std::move(folder)) {}

std::string Autosave::sessionPath() const {
    return (fs::path(m_folder) / "recovery.faultline.json").string();
}

bool Autosave::tick(const Session& session, std::chrono::steady_clock::time_point now) {
    if (m_lastSave == std::chrono::steady_clock::time_point{})
        m_lastSave = now; // the first interval starts with the session
    if (now - m_lastSave < kInterval || session.version() == m_savedVersion)
        return false;
    m_lastSave = now;
    return saveNow(session, false);
}

bool Autosave::saveNow(const Session& session, bool cleanExit) {
    try {
        saveSessionFile(session.state(), sessionPath());
        const Json marker = {{"session", "recovery.faultline.json"},
                             {"clean_exit", cleanExit},
                             {"saved_at", nowIso()}};
        writeFileAtomically(markerPath(m_folder), marker.dump(1) + "\n");
        m_savedVersion = session.version();
        m_lastError.clear();
        return true;
    } catch (const std::exception& e) {
        m_lastError = e.what();
        return false;
    }
}

std::optional<PendingRecovery> Autosave::pending() const {
    try {
        const std::string text = readFileBytes(markerPath(m_folder));
        const Json marker = parseJsonText(text, markerPath(m_folder));
        if (!marker.is_object() || marker.value("clean_exit", true))
            return std::nullopt;
        if (!fs::exists(sessionPath()))
            return std::nullopt;
        return PendingRecovery{sessionPath(), marker.value("saved_at", std::string())};
    } catch (const std::exception&) {
        return std::nullopt; // no marker, or a damaged one: nothing to offer
    }
}

void Autosave::discard() {
    std::error_code ec;
    fs::remove(markerPath(m_folder), ec);
}

} // namespace faultline::core
