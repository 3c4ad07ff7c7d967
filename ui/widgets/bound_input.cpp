#include "ui/widgets/bound_input.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace faultline::ui {

namespace {
constexpr double kOpen = 1e30;
}

bool boundInput(const char* id, double* value, bool isHigh, bool integer, float width) {
    ImGuiStorage* storage = ImGui::GetStateStorage();
    ImGui::PushID(id);
    const ImGuiID editingKey = ImGui::GetID("##editing");
    // The text shown: kept while the field is being edited, rebuilt from the value otherwise.
    static char buffer[64];
    char shown[64];
    if (std::fabs(*value) >= kOpen)
        shown[0] = '\0';
    else if (integer)
        std::snprintf(shown, sizeof shown, "%.0f", *value);
    else
        std::snprintf(shown, sizeof shown, "%.6g", *value);
    const bool editing = storage->GetBool(editingKey, false);
    char* text = editing ? buffer : shown;
    ImGui::SetNextItemWidth(width);
    ImGui::InputTextWithHint("##bound", isHigh ? "max" : "min", text, 64,
                             ImGuiInputTextFlags_CharsScientific);
    if (ImGui::IsItemActivated()) {
        std::memcpy(buffer, shown, sizeof buffer);
        storage->SetBool(editingKey, true);
    }
    bool committed = false;
    if (ImGui::IsItemDeactivated()) {
        storage->SetBool(editingKey, false);
        double next = *value;
        if (buffer[0] == '\0') {
            next = isHigh ? kOpen : -kOpen;
        } else {
            char* end = nullptr;
            const double parsed = std::strtod(buffer, &end);
            if (end != buffer && std::isfinite(parsed))
                next = integer ? (isHigh ? std::floor(parsed) : std::ceil(parsed)) : parsed;
        }
        if (next != *value) {
            *value = next;
            committed = true;
        }
    }
    ImGui::PopID();
    return committed;
}

} // namespace faultline::ui
