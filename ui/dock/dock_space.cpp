#include "ui/dock/dock_space.hpp"
#include "ui/widgets/text_fit.hpp"

#include "ui/widgets/item_registry.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace faultline::ui {

namespace {

constexpr float kEdgeZone = 0.28f; // a drop within this share of an area's edge splits it

ImU32 color(ImGuiCol c, float alpha = 1.0f) { return ImGui::GetColorU32(c, alpha); }

} // namespace

void DockSpace::place(DockNode& node, ImVec2 min, ImVec2 max, float bar, float minSize) {
    if (node.isLeaf()) {
        m_areas.push_back({&node, min, max});
        return;
    }
    const bool h = node.split == SplitAxis::Horizontal;
    const float total = (h ? max.x - min.x : max.y - min.y) - bar;
    float first = total * node.ratio;
    if (total > 2 * minSize)
        first = std::clamp(first, minSize, total - minSize);
    first = std::floor(first);
    ImVec2 aMax = h ? ImVec2(min.x + first, max.y) : ImVec2(max.x, min.y + first);
    ImVec2 barMin = h ? ImVec2(aMax.x, min.y) : ImVec2(min.x, aMax.y);
    ImVec2 barMax = h ? ImVec2(aMax.x + bar, max.y) : ImVec2(max.x, aMax.y + bar);
    ImVec2 bMin = h ? ImVec2(barMax.x, min.y) : ImVec2(min.x, barMax.y);
    m_splitters.push_back({&node, barMin, barMax, min, max});
    place(*node.first, min, aMax, bar, minSize);
    place(*node.second, bMin, max, bar, minSize);
}

std::optional<DockSpace::Drop> DockSpace::dropAt(ImVec2 mouse, float tabBarHeight) const {
    for (const auto& a : m_areas) {
        if (mouse.x < a.min.x || mouse.x >= a.max.x || mouse.y < a.min.y || mouse.y >= a.max.y)
            continue;
        Drop d{a.node->id, DropSide::Centre, a.min, a.max};
        const float w = a.max.x - a.min.x, h = a.max.y - a.min.y;
        if (mouse.y < a.min.y + tabBarHeight || a.node->tabs.empty())
            return d; // over the tab bar: join the tabs
        const float u = (mouse.x - a.min.x) / w, v = (mouse.y - a.min.y) / h;
        const float edges[4] = {u, 1 - u, v, 1 - v};
        const int nearest = static_cast<int>(std::min_element(edges, edges + 4) - edges);
        if (edges[nearest] > kEdgeZone)
            return d;
        const float sw = w * 0.3f, sh = h * 0.3f;
        switch (nearest) {
        case 0:
            d.side = DropSide::Left, d.max.x = a.min.x + sw;
            break;
        case 1:
            d.side = DropSide::Right, d.min.x = a.max.x - sw;
            break;
        case 2:
            d.side = DropSide::Top, d.max.y = a.min.y + sh;
            break;
        default:
            d.side = DropSide::Bottom, d.min.y = a.max.y - sh;
            break;
        }
        return d;
    }
    return std::nullopt;
}

bool DockSpace::drawTabs(DockLayout& layout, DockNode& area, ImVec2 min, float width, float scale,
                         const Callbacks& cb, ItemRegistry* items) {
    bool changed = false;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImGuiStyle& style = ImGui::GetStyle();
    const float height = ImGui::GetFrameHeight() + 2 * scale;
    dl->AddRectFilled(min, ImVec2(min.x + width, min.y + height), color(ImGuiCol_TitleBg));
    float x = min.x + 2 * scale;
    const float padX = 10 * scale;
    // Tabs that do not all fit (a narrow column of many panels): as many as fit, the active one
    // among them, and a button at the end listing every panel of the area.
    float needed = 2 * scale;
    for (const std::string& panel : area.tabs)
        needed += ImGui::CalcTextSize(cb.titleOf(panel)).x + 2 * padX + 2 * scale;
    const bool overflow = needed > width;
    const float listW = overflow ? ImGui::GetFrameHeight() + 2 * scale : 0.0f;
    std::vector<std::string> shown;
    {
        float used = 2 * scale;
        for (const std::string& panel : area.tabs) {
            const float w = ImGui::CalcTextSize(cb.titleOf(panel)).x + 2 * padX + 2 * scale;
            if (used + w > width - listW)
                break;
            shown.push_back(panel);
            used += w;
        }
        if (overflow && std::find(shown.begin(), shown.end(), area.active) == shown.end() &&
            !area.active.empty()) {
            const float activeW =
                ImGui::CalcTextSize(cb.titleOf(area.active)).x + 2 * padX + 2 * scale;
            while (!shown.empty() && used + activeW > width - listW) {
                used -= ImGui::CalcTextSize(cb.titleOf(shown.back())).x + 2 * padX + 2 * scale;
                shown.pop_back();
            }
            shown.push_back(area.active);
        }
        if (!overflow)
            shown = area.tabs;
    }
    std::string toClose;
    for (const std::string& panel : shown) {
        const char* title = cb.titleOf(panel);
        const float textW = ImGui::CalcTextSize(title).x;
        float tabW =
            std::min(textW + 2 * padX, std::max(40 * scale, min.x + width - listW - x - 2 * scale));
        if (tabW < 24 * scale)
            break;
        ImGui::SetCursorScreenPos(ImVec2(x, min.y + 2 * scale));
        ImGui::PushID(panel.c_str());
        ImGui::InvisibleButton("##tab", ImVec2(tabW, height - 2 * scale));
        const bool hovered = ImGui::IsItemHovered();
        if (items)
            items->markLastItem("tab." + panel);
        if (ImGui::IsItemActivated())
            m_pressedPanel = panel;
        if (ImGui::IsItemClicked(ImGuiMouseButton_Left) && area.active != panel) {
            area.active = panel;
        }
        if (ImGui::IsItemActive() && m_dragPanel.empty() && m_pressedPanel == panel &&
            ImGui::IsMouseDragging(ImGuiMouseButton_Left, 8 * scale))
            m_dragPanel = panel;
        if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Middle))
            toClose = panel;
        if (ImGui::BeginPopupContextItem("##tabmenu")) {
            if (ImGui::MenuItem("Close panel"))
                toClose = panel;
            ImGui::EndPopup();
        }
        const bool active = area.active == panel;
        const ImVec2 a(x, min.y + 3 * scale), b(x + tabW, min.y + height);
        ImU32 bg = active    ? color(ImGuiCol_WindowBg)
                   : hovered ? color(ImGuiCol_TabHovered)
                             : color(ImGuiCol_Tab);
        dl->AddRectFilled(a, b, bg, 4 * scale, ImDrawFlags_RoundCornersTop);
        if (active)
            dl->AddRectFilled(a, ImVec2(b.x, a.y + 2 * scale), color(ImGuiCol_TabActive), 4 * scale,
                              ImDrawFlags_RoundCornersTop);
        ImGui::PushClipRect(a, b, true);
        const ImU32 textColor = active ? color(ImGuiCol_Text) : color(ImGuiCol_Text, 0.72f);
        // A tab narrower than its title shows it shortened (all of it on hover).
        const std::string shownTitle = elided(title, tabW - 2 * padX);
        dl->AddText(ImVec2(x + padX, a.y + (b.y - a.y - ImGui::GetTextLineHeight()) * 0.5f),
                    textColor, shownTitle.c_str());
        if (hovered && shownTitle != title)
            ImGui::SetTooltip("%s", title);
        ImGui::PopClipRect();
        ImGui::PopID();
        x += tabW + 2 * scale;
    }
    if (overflow) {
        const float bw = ImGui::GetFrameHeight();
        ImGui::SetCursorScreenPos(ImVec2(min.x + width - bw - 2 * scale, min.y + 2 * scale));
        ImGui::PushID(area.id);
        if (ImGui::Button("\xC2\xBB", ImVec2(bw, height - 4 * scale))) // a right guillemet
            ImGui::OpenPopup("##alltabs");
        if (items)
            items->markLastItem("tabs.more." + std::to_string(area.id));
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Every panel here");
        if (ImGui::BeginPopup("##alltabs")) {
            for (const std::string& panel : area.tabs) {
                if (ImGui::Selectable(cb.titleOf(panel), area.active == panel))
                    area.active = panel;
                if (items)
                    items->markLastItem("tabs.list." + panel);
            }
            ImGui::EndPopup();
        }
        ImGui::PopID();
    }
    (void)style;
    if (!toClose.empty()) {
        layout.closePanel(toClose);
        changed = true;
    }
    return changed;
}

bool DockSpace::draw(DockLayout& layout, ImVec2 pos, ImVec2 size, float scale, const Callbacks& cb,
                     ItemRegistry* items) {
    m_areas.clear();
    m_splitters.clear();
    const float bar = std::max(4.0f, std::round(5 * scale));
    place(layout.root(), pos, ImVec2(pos.x + size.x, pos.y + size.y), bar, 80 * scale);
    bool changed = false;
    const float tabBarHeight = ImGui::GetFrameHeight() + 2 * scale;

    // Splitters first, so the areas drawn after do not steal their clicks.
    for (const auto& s : m_splitters) {
        ImGui::SetCursorScreenPos(s.min);
        ImGui::PushID(s.node->id);
        const ImVec2 sz(std::max(1.0f, s.max.x - s.min.x), std::max(1.0f, s.max.y - s.min.y));
        ImGui::InvisibleButton("##splitter", sz);
        const bool h = s.node->split == SplitAxis::Horizontal;
        if (ImGui::IsItemHovered() || ImGui::IsItemActive())
            ImGui::SetMouseCursor(h ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
        if (items)
            items->markLastItem("splitter." + std::to_string(s.node->id));
        if (ImGui::IsItemActive()) {
            const float total =
                (h ? s.parentMax.x - s.parentMin.x : s.parentMax.y - s.parentMin.y) - bar;
            const float at = (h ? ImGui::GetIO().MousePos.x - s.parentMin.x
                                : ImGui::GetIO().MousePos.y - s.parentMin.y) -
                             bar * 0.5f;
            if (total > 0)
                s.node->ratio = std::clamp(at / total, 0.05f, 0.95f);
        }
        if (ImGui::IsItemDeactivated())
            changed = true;
        const bool lit = ImGui::IsItemHovered() || ImGui::IsItemActive();
        ImGui::GetWindowDrawList()->AddRectFilled(
            s.min, s.max,
            color(lit ? ImGuiCol_SeparatorHovered : ImGuiCol_Separator, lit ? 1.0f : 0.35f));
        ImGui::PopID();
    }

    if (m_areas.size() == 1 && m_areas.front().node->tabs.empty()) {
        const char* hint =
            "No panels are open: choose them in View > Panels, or View > Reset layout.";
        const ImVec2 t = ImGui::CalcTextSize(hint);
        ImGui::GetWindowDrawList()->AddText(
            ImVec2(pos.x + (size.x - t.x) / 2, pos.y + (size.y - t.y) / 2),
            color(ImGuiCol_TextDisabled), hint);
    }

    for (const auto& a : m_areas) {
        DockNode& area = *a.node;
        if (area.tabs.empty())
            continue;
        const float w = a.max.x - a.min.x, h = a.max.y - a.min.y;
        ImGui::SetCursorScreenPos(a.min);
        ImGui::PushID(area.id);
        ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
        ImGui::PushStyleColor(ImGuiCol_ChildBg, ImGui::GetStyleColorVec4(ImGuiCol_WindowBg));
        ImGui::BeginChild("##area", ImVec2(w, h), false,
                          ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
        ImGui::PopStyleColor();
        ImGui::PopStyleVar();
        if (drawTabs(layout, area, a.min, w, scale, cb, items)) {
            changed = true;
            ImGui::EndChild();
            ImGui::PopID();
            break; // the tree changed under us; the next frame draws it
        }
        const std::string panel = area.active;
        const bool padded = cb.padded(panel);
        ImGui::SetCursorScreenPos(ImVec2(a.min.x, a.min.y + tabBarHeight));
        if (!padded)
            ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
        ImGui::BeginChild(
            ("##content." + panel).c_str(), ImVec2(w, h - tabBarHeight), false,
            ImGuiWindowFlags_AlwaysUseWindowPadding |
                (padded ? 0 : ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse));
        if (!padded)
            ImGui::PopStyleVar();
        cb.drawPanel(panel);
        ImGui::EndChild();
        ImGui::EndChild();
        ImGui::PopID();
    }

    // A tab being dragged: a ghost label at the cursor and where it would land.
    if (!m_dragPanel.empty()) {
        ImDrawList* fg = ImGui::GetForegroundDrawList();
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        auto drop = dropAt(mouse, tabBarHeight);
        if (drop) {
            fg->AddRectFilled(drop->min, drop->max, color(ImGuiCol_DragDropTarget, 0.18f));
            fg->AddRect(drop->min, drop->max, color(ImGuiCol_DragDropTarget, 0.9f), 0, 0,
                        2 * scale);
        }
        const char* title = cb.titleOf(m_dragPanel);
        const ImVec2 t = ImGui::CalcTextSize(title);
        const ImVec2 a(mouse.x + 12 * scale, mouse.y + 8 * scale);
        fg->AddRectFilled(a, ImVec2(a.x + t.x + 16 * scale, a.y + t.y + 8 * scale),
                          color(ImGuiCol_PopupBg), 4 * scale);
        fg->AddRect(a, ImVec2(a.x + t.x + 16 * scale, a.y + t.y + 8 * scale),
                    color(ImGuiCol_Border), 4 * scale);
        fg->AddText(ImVec2(a.x + 8 * scale, a.y + 4 * scale), color(ImGuiCol_Text), title);
        ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
            if (drop && layout.movePanel(m_dragPanel, drop->area, drop->side))
                changed = true;
            m_dragPanel.clear();
            m_pressedPanel.clear();
        }
    }
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left) && m_dragPanel.empty())
        m_pressedPanel.clear();
    return changed;
}

} // namespace faultline::ui
