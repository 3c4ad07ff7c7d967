// Help > Keyboard and mouse (the key table, with where the run's journal is written) and
// Help > About.
#pragma once

#include "ui/workbench/key_commands.hpp"

#include <string>
#include <vector>

namespace faultline::ui {

class ViewRenderer;

class HelpWindows {
  public:
    bool showKeys = false;
    bool showAbout = false;
    // `journalPath`: where this run's journal goes (empty: not written); `renderer` for About.
    void draw(const std::vector<KeyCommand>& keys, float scale, const std::string& journalPath,
              const ViewRenderer* renderer);
};

} // namespace faultline::ui
