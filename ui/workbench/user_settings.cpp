#include "ui/workbench/user_settings.hpp"

#include "core/session/atomic_file.hpp"
#include "core/session/command_args.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace faultline::ui {

namespace fs = std::filesystem;
using core::Json;

namespace {
constexpr std::size_t kRecentFiles = 10;
}

UserSettings::UserSettings(std::string configDir) : m_configDir(std::move(configDir)) { load(); }

void UserSettings::addRecent(const std::string& path) {
    if (path.empty())
        return;
    std::erase(m_recent, path);
    m_recent.insert(m_recent.begin(), path);
    if (m_recent.size() > kRecentFiles)
        m_recent.resize(kRecentFiles);
    save();
}

void UserSettings::setFrameBudget(std::size_t bytes) {
    m_frameBudget = bytes;
    save();
}

void UserSettings::load() {
    if (m_configDir.empty())
        return;
    std::ifstream in(fs::path(m_configDir) / "settings.json");
    if (!in)
        return;
    std::stringstream text;
    text << in.rdbuf();
    try {
        const Json doc = Json::parse(text.str());
        if (doc.contains("recent") && doc["recent"].is_array())
            for (const Json& r : doc["recent"])
                if (r.is_string() && m_recent.size() < kRecentFiles)
                    m_recent.push_back(r.get<std::string>());
        if (doc.contains("frame_memory_mb") && doc["frame_memory_mb"].is_number_unsigned())
            m_frameBudget = doc["frame_memory_mb"].get<std::size_t>() << 20;
    } catch (const std::exception&) {
        // A damaged settings file only loses the recent list.
    }
}

void UserSettings::save() const {
    if (m_configDir.empty())
        return;
    try {
        std::error_code ec;
        fs::create_directories(m_configDir, ec);
        core::writeFileAtomically(
            (fs::path(m_configDir) / "settings.json").string(),
            Json{{"recent", m_recent}, {"frame_memory_mb", m_frameBudget >> 20}}.dump(2));
    } catch (const std::exception&) {
        // Not worth interrupting the user for.
    }
}

} // namespace faultline::ui
