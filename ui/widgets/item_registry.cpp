#include "ui/widgets/item_registry.hpp"

#include <imgui.h>

namespace faultline::ui {

void ItemRegistry::markLastItem(const std::string& name) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    m_current[name] = {a.x, a.y, b.x, b.y};
}

std::optional<ItemRect> ItemRegistry::find(const std::string& name) const {
    auto it = m_last.find(name);
    if (it == m_last.end())
        return std::nullopt;
    return it->second;
}

} // namespace faultline::ui
