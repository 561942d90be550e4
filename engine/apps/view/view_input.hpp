// The viewer's input as the window delivers it (keys by name, drags and the wheel summed),
// applied once per shown frame; a script (view_script.hpp) feeds the same.
#pragma once

#include <deque>
#include <string>

struct GLFWwindow;

namespace pathlet::view {

struct Input {
    std::deque<std::string> keys;  // "space", "left", "s", "?", "tab", ...
    bool shift = false;
    float orbit_dx = 0, orbit_dy = 0, pan_dx = 0, pan_dy = 0, scroll = 0;
    double last_x = 0, last_y = 0;
    int dragging = -1;  // GLFW mouse button held, -1 none
};

// The window's key, mouse button, cursor and scroll callbacks, writing into the Input that is
// the window's user pointer; what the panels take (ui_wants_*) does not reach it.
void install_input_callbacks(GLFWwindow* w);

}  // namespace pathlet::view
