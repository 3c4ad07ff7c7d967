#include "ui/app/theme.hpp"

#include <imgui.h>

#include <filesystem>

namespace faultline::ui {

namespace {

ImVec4 rgb(int r, int g, int b, float a = 1.0f) {
    return ImVec4(r / 255.0f, g / 255.0f, b / 255.0f, a);
}

const char* kFontPaths[] = {
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
};

} // namespace

void applyTheme(float scale) {
    ImGuiStyle& s = ImGui::GetStyle();
    s = ImGuiStyle();
    ImGui::StyleColorsLight(&s);
    s.WindowPadding = ImVec2(10, 8);
    s.FramePadding = ImVec2(7, 4);
    s.ItemSpacing = ImVec2(8, 6);
    s.ItemInnerSpacing = ImVec2(5, 4);
    s.CellPadding = ImVec2(5, 3);
    s.IndentSpacing = 16;
    s.ScrollbarSize = 12;
    s.GrabMinSize = 10;
    s.WindowRounding = 0;
    s.ChildRounding = 0;
    s.FrameRounding = 3;
    s.PopupRounding = 4;
    s.ScrollbarRounding = 6;
    s.GrabRounding = 3;
    s.TabRounding = 3;
    s.WindowBorderSize = 0;
    s.ChildBorderSize = 1;
    s.PopupBorderSize = 1;
    s.FrameBorderSize = 1;
    s.WindowMenuButtonPosition = ImGuiDir_None;

    const ImVec4 accent = rgb(52, 110, 190);
    ImVec4* c = s.Colors;
    c[ImGuiCol_Text] = rgb(31, 35, 41);
    c[ImGuiCol_TextDisabled] = rgb(112, 119, 130);
    c[ImGuiCol_WindowBg] = rgb(248, 249, 251);
    c[ImGuiCol_ChildBg] = rgb(248, 249, 251, 0.0f);
    c[ImGuiCol_PopupBg] = rgb(255, 255, 255);
    c[ImGuiCol_BorderShadow] = rgb(0, 0, 0, 0);
    c[ImGuiCol_Border] = rgb(196, 202, 210);
    c[ImGuiCol_FrameBg] = rgb(233, 236, 240);
    c[ImGuiCol_FrameBgHovered] = rgb(221, 227, 234);
    c[ImGuiCol_FrameBgActive] = rgb(208, 216, 226);
    c[ImGuiCol_TitleBg] = rgb(226, 229, 234);
    c[ImGuiCol_TitleBgActive] = rgb(214, 219, 227);
    c[ImGuiCol_TitleBgCollapsed] = rgb(226, 229, 234);
    c[ImGuiCol_MenuBarBg] = rgb(236, 238, 242);
    c[ImGuiCol_ScrollbarBg] = rgb(0, 0, 0, 0);
    c[ImGuiCol_ScrollbarGrab] = rgb(190, 196, 205);
    c[ImGuiCol_ScrollbarGrabHovered] = rgb(170, 177, 188);
    c[ImGuiCol_ScrollbarGrabActive] = rgb(150, 158, 170);
    c[ImGuiCol_CheckMark] = accent;
    c[ImGuiCol_SliderGrab] = accent;
    c[ImGuiCol_SliderGrabActive] = rgb(34, 84, 152);
    c[ImGuiCol_Button] = rgb(225, 229, 234);
    c[ImGuiCol_ButtonHovered] = rgb(207, 216, 227);
    c[ImGuiCol_ButtonActive] = rgb(185, 199, 216);
    c[ImGuiCol_Header] = rgb(210, 222, 238);
    c[ImGuiCol_HeaderHovered] = rgb(195, 212, 234);
    c[ImGuiCol_HeaderActive] = rgb(175, 198, 228);
    c[ImGuiCol_Separator] = rgb(200, 205, 212);
    c[ImGuiCol_SeparatorHovered] = accent;
    c[ImGuiCol_SeparatorActive] = accent;
    c[ImGuiCol_ResizeGrip] = rgb(0, 0, 0, 0);
    c[ImGuiCol_Tab] = rgb(214, 219, 226);
    c[ImGuiCol_TabHovered] = rgb(200, 210, 223);
    c[ImGuiCol_TabActive] = accent;
    c[ImGuiCol_TabUnfocused] = rgb(214, 219, 226);
    c[ImGuiCol_TabUnfocusedActive] = accent;
    c[ImGuiCol_PlotHistogram] = accent;
    c[ImGuiCol_PlotHistogramHovered] = rgb(34, 84, 152);
    c[ImGuiCol_TableHeaderBg] = rgb(228, 231, 236);
    c[ImGuiCol_TableBorderStrong] = rgb(200, 205, 212);
    c[ImGuiCol_TableBorderLight] = rgb(222, 226, 231);
    c[ImGuiCol_TableRowBg] = rgb(0, 0, 0, 0);
    c[ImGuiCol_TableRowBgAlt] = rgb(0, 0, 0, 0.025f);
    c[ImGuiCol_TextSelectedBg] = rgb(52, 110, 190, 0.3f);
    c[ImGuiCol_DragDropTarget] = accent;
    c[ImGuiCol_NavHighlight] = accent;
    c[ImGuiCol_ModalWindowDimBg] = rgb(20, 24, 30, 0.35f);
    s.ScaleAllSizes(scale);
}

bool loadFonts(float scale) {
    ImGuiIO& io = ImGui::GetIO();
    io.Fonts->Clear();
    for (const char* path : kFontPaths) {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec))
            continue;
        ImFontConfig config;
        config.OversampleH = 2;
        config.OversampleV = 2;
        if (io.Fonts->AddFontFromFileTTF(path, 15.0f * scale, &config))
            return true;
    }
    ImFontConfig config;
    config.SizePixels = 13.0f * scale;
    io.Fonts->AddFontDefault(&config);
    return false;
}

} // namespace faultline::ui
