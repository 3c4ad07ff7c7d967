// ItemRegistry: where named widgets were drawn this frame, so tests (headless or under Xvfb)
// can move the mouse onto "boxes.add" instead of guessing pixels. Costs a map insert per mark.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace faultline::ui {

struct ItemRect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    float cx() const { return 0.5f * (x0 + x1); }
    float cy() const { return 0.5f * (y0 + y1); }
};

class ItemRegistry {
  public:
    // Records ImGui's last item under `name` (the last one wins within a frame).
    void markLastItem(const std::string& name);
    void mark(const std::string& name, ItemRect rect) { m_current[name] = rect; }
    // Rects of the previous complete frame.
    std::optional<ItemRect> find(const std::string& name) const;
    void endFrame() { m_last.swap(m_current), m_current.clear(); }
    const std::map<std::string, ItemRect>& all() const { return m_last; }

  private:
    std::map<std::string, ItemRect> m_current, m_last;
};

} // namespace faultline::ui
