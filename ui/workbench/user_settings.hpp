// What the workbench remembers for the user between runs, apart from any session: the files
// opened lately (File > Open recent) and the memory frames may take. Kept in
// <configDir>/settings.json, written atomically on every change; a damaged or missing file
// only loses what it held. One of the Workbench's parts with one job each (issue 39).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace faultline::ui {

class UserSettings {
  public:
    // An empty folder keeps nothing (tests, --no-config runs).
    explicit UserSettings(std::string configDir);

    const std::vector<std::string>& recent() const { return m_recent; }
    // `path` first in the list (at most 10, no repeats); empty paths are ignored.
    void addRecent(const std::string& path);
    // Bytes frames may take; 0 for the default (a quarter of RAM).
    std::size_t frameBudget() const { return m_frameBudget; }
    void setFrameBudget(std::size_t bytes);

  private:
    void load();
    void save() const;
    std::string m_configDir;
    std::vector<std::string> m_recent;
    std::size_t m_frameBudget = 0;
};

} // namespace faultline::ui
