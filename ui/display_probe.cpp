#include "ui/display_probe.hpp"

#include <GLFW/glfw3.h>

#include <cstdlib>

namespace faultline::ui {

bool displayAvailable(std::string& why) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        why = "no display (DISPLAY is not set)";
        return false;
    }
    if (!glfwInit()) {
        const char* description = nullptr;
        glfwGetError(&description);
        why = std::string("cannot open the display: ") + (description ? description : "unknown");
        return false;
    }
    return true;
}

} // namespace faultline::ui
