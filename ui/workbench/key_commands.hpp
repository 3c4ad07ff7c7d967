// A keyboard command of the workbench: shown in the help window and the menus, run by its keys.
// Entries without a key are mouse gestures, listed in the help only. The table is
// Workbench::keyCommands() (workbench_keys.cpp): the handler, the help and the menus all read
// it, so a shortcut cannot be documented one way and work another.
#pragma once

namespace faultline::ui {

class Workbench;

struct KeyCommand {
    const char* id;   // how menus name it ("" for gestures)
    const char* keys; // as shown: "Ctrl+Shift+O"
    const char* what;
    int key = 0;         // GLFW key code (the ImGui back end's key indices); 0: a gesture
    bool ctrl = false;   // held, or not
    int shift = -1;      // 1 held, 0 not, -1 either
    bool repeat = false; // fires again while held
    void (*run)(Workbench&) = nullptr;
};

} // namespace faultline::ui
