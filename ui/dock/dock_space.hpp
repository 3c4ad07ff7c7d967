// DockSpace: draws a DockLayout with ImGui inside the current window: one child per area with a
// tab bar, splitter bars between areas, and tab dragging (onto an area's centre to join its tabs,
// onto an edge to split it). Layout changes are reported once the mouse is released.
#pragma once

#include "ui/dock/dock_layout.hpp"

#include <imgui.h>

#include <functional>
#include <string>

namespace faultline::ui {

class ItemRegistry;

class DockSpace {
  public:
    struct Callbacks {
        std::function<void(const std::string& panel)> drawPanel;
        std::function<const char*(const std::string& panel)> titleOf;
        std::function<bool(const std::string& panel)> padded;
    };

    // Draws `layout` in the rectangle [pos, pos + size) (screen coordinates). Returns true when
    // the user finished a change (tab moved or closed, splitter released): commit it then.
    bool draw(DockLayout& layout, ImVec2 pos, ImVec2 size, float scale, const Callbacks& cb,
              ItemRegistry* items);

    bool dragging() const { return !m_dragPanel.empty(); }
    // The drop a release at `mouse` would make (for tests and the drop preview).
    struct Drop {
        int area = 0;
        DropSide side = DropSide::Centre;
        ImVec2 min, max; // preview rectangle
    };

  private:
    struct AreaRect {
        DockNode* node;
        ImVec2 min, max;
    };
    struct SplitterRect {
        DockNode* node;
        ImVec2 min, max; // the bar
        ImVec2 parentMin, parentMax;
    };
    void place(DockNode& node, ImVec2 min, ImVec2 max, float bar, float minSize);
    bool drawTabs(DockLayout& layout, DockNode& area, ImVec2 min, float width, float scale,
                  const Callbacks& cb, ItemRegistry* items);
    std::optional<Drop> dropAt(ImVec2 mouse, float tabBarHeight) const;

    std::vector<AreaRect> m_areas;
    std::vector<SplitterRect> m_splitters;
    std::string m_dragPanel;
    std::string m_pressedPanel;
};

} // namespace faultline::ui
