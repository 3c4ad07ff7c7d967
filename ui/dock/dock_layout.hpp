// DockLayout: the workbench's panel arrangement as a split tree. A leaf is an area holding tabs
// (panel ids); an inner node splits its rectangle in two. Plain data with a JSON form, so the
// layout is saved in the session (layout.set) and restored; no ImGui here.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace faultline::ui {

enum class SplitAxis {
    None,       // a leaf: an area with tabs
    Horizontal, // children side by side (first on the left)
    Vertical,   // children stacked (first on top)
};

// Where a dragged tab lands relative to an area: into its tab bar, or a new area on one side.
enum class DropSide { Centre, Left, Right, Top, Bottom };

struct DockNode {
    int id = 0; // unique within a layout, stable while the layout lives (ImGui ids)
    SplitAxis split = SplitAxis::None;
    float ratio = 0.5f; // the first child's share of the size along the split
    std::unique_ptr<DockNode> first, second;
    std::vector<std::string> tabs; // leaves only
    std::string active;            // leaves only: the tab shown

    bool isLeaf() const { return split == SplitAxis::None; }
};

class DockLayout {
  public:
    DockLayout();
    DockLayout(const DockLayout& other);
    DockLayout& operator=(const DockLayout& other);

    // Data, boxes and thresholds on the left, the viewports large in the centre above the
    // timeline, histograms and faults on the right.
    static DockLayout defaultLayout();
    // The default for a window this many logical pixels wide: below kCompactWidth one column of
    // every side panel as tabs (about 260 pixels, the width the panels are laid out for) beside
    // the views, instead of two columns too narrow to read (issue 41: a 640x420 window).
    static constexpr float kCompactWidth = 1000.0f;
    static DockLayout defaultLayout(float windowWidth);

    // Builds a layout from its JSON form. Unknown or repeated panels are dropped, ratios are
    // clamped and empty areas removed; nullopt (with the reason) when the document is not a
    // layout. `known` lists the panel ids that exist.
    static std::optional<DockLayout> fromJson(const nlohmann::json& doc,
                                              const std::vector<std::string>& known,
                                              std::string* why = nullptr);
    nlohmann::json toJson() const;

    DockNode& root() { return *m_root; }
    const DockNode& root() const { return *m_root; }
    std::vector<DockNode*> areas();
    DockNode* node(int id);
    DockNode* areaOf(const std::string& panel);
    bool contains(const std::string& panel) const;

    // Moves a panel (from wherever it is, or from closed) into `areaId`'s tabs or onto one of
    // its sides as a new area taking `share` of the space. False when nothing changes.
    bool movePanel(const std::string& panel, int areaId, DropSide side, float share = 0.3f);
    bool closePanel(const std::string& panel);
    // Opens a closed panel in the area it would have in the default layout's neighbourhood
    // (the area holding its default neighbours), else the largest area.
    void openPanel(const std::string& panel);
    void setActive(const std::string& panel);

    // Panel settings kept with the layout (e.g. which histograms are shown), by panel id.
    nlohmann::json& panelSettings(const std::string& panel);
    const nlohmann::json* panelSettings(const std::string& panel) const;

  private:
    void collapseEmpty();
    int nextId();
    std::unique_ptr<DockNode> m_root;
    std::map<std::string, nlohmann::json> m_settings;
    int m_nextId = 1;
};

} // namespace faultline::ui
