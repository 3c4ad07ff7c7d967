#include "ui/widgets/number_field.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace faultline::ui {

namespace {

// The field's text while it is being edited (one field is edited at a time).
char g_buffer[64];

// Draws the field; returns the text committed (Enter or leaving), or nullptr. Escape reverts
// the text to `shown` (ImGui does), so committing that text changes nothing.
const char* textField(const char* label, const char* shown, const char* hint, float width) {
    ImGuiStorage* storage = ImGui::GetStateStorage();
    ImGui::PushID(label);
    const ImGuiID editingKey = ImGui::GetID("##editing");
    ImGui::PopID();
    const bool editing = storage->GetBool(editingKey, false);
    char local[64];
    std::snprintf(local, sizeof local, "%s", shown);
    char* text = editing ? g_buffer : local;
    if (width > 0.0f)
        ImGui::SetNextItemWidth(width);
    const ImGuiInputTextFlags flags =
        ImGuiInputTextFlags_CharsScientific | ImGuiInputTextFlags_AutoSelectAll;
    if (hint)
        ImGui::InputTextWithHint(label, hint, text, sizeof g_buffer, flags);
    else
        ImGui::InputText(label, text, sizeof g_buffer, flags);
    if (ImGui::IsItemActivated()) {
        std::memcpy(g_buffer, local, sizeof g_buffer);
        storage->SetBool(editingKey, true);
    }
    if (ImGui::IsItemDeactivated()) {
        storage->SetBool(editingKey, false);
        return g_buffer;
    }
    return nullptr;
}

} // namespace

bool numberField(const char* label, double* value, const char* format, float width,
                 const char* empty, double emptyValue) {
    char shown[64];
    if (empty && *value == emptyValue)
        shown[0] = '\0';
    else
        std::snprintf(shown, sizeof shown, format, *value);
    const char* typed = textField(label, shown, empty, width);
    if (!typed)
        return false;
    double next = *value;
    if (typed[0] == '\0' && empty) {
        next = emptyValue;
    } else {
        char* end = nullptr;
        const double parsed = std::strtod(typed, &end);
        if (end == typed || !std::isfinite(parsed) || std::strcmp(typed, shown) == 0)
            return false; // not a number, or untouched (the text shown rounds the value)
        next = parsed;
    }
    if (next == *value)
        return false;
    *value = next;
    return true;
}

bool numberField(const char* label, int* value, float width) {
    char shown[32];
    std::snprintf(shown, sizeof shown, "%d", *value);
    const char* typed = textField(label, shown, nullptr, width);
    if (!typed || std::strcmp(typed, shown) == 0)
        return false;
    char* end = nullptr;
    const long parsed = std::strtol(typed, &end, 10);
    if (end == typed || parsed == *value || parsed > 2000000000L || parsed < -2000000000L)
        return false;
    *value = static_cast<int>(parsed);
    return true;
}

} // namespace faultline::ui
