// FileDialog: a small ImGui file chooser (a modal): folder path, listing, file name, filter by
// extension. Data may be given as a glob pattern ("dump.*.gz") typed into the name field.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace faultline::ui {

class ItemRegistry;

class FileDialog {
  public:
    enum class Mode { Open, Save };

    // `extensions` (e.g. {".faultline.json"}) filter the listing unless "All files" is ticked;
    // the first is appended to a saved name that has none.
    void open(std::string title, Mode mode, std::string purpose,
              std::vector<std::string> extensions, std::string directory,
              std::string fileName = "");
    // Draws the dialog when open; true once when the user accepted (see path()).
    bool draw(float scale, ItemRegistry* items);
    bool isOpen() const { return m_open; }
    const std::string& purpose() const { return m_purpose; }
    const std::string& directory() const { return m_directory; } // the folder listed
    const std::string& path() const { return m_result; }

  private:
    struct Entry {
        std::string name;
        bool directory = false;
        std::uintmax_t size = 0;
    };
    void list();
    bool accept();
    bool matches(const std::string& name) const;

    bool m_open = false, m_justOpened = false, m_allFiles = false;
    Mode m_mode = Mode::Open;
    std::string m_title, m_purpose, m_directory, m_directoryInput, m_fileName, m_result, m_problem;
    std::string m_suggested; // the name as suggested, until the user's first edit replaces it
    std::vector<std::string> m_extensions;
    std::vector<Entry> m_entries;
};

} // namespace faultline::ui
