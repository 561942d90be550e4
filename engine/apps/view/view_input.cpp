#include "view/view_input.hpp"

#include "view/view_window.hpp"

#include <GLFW/glfw3.h>

namespace pathlet::view {
namespace {

Input& input_of(GLFWwindow* w) { return *static_cast<Input*>(glfwGetWindowUserPointer(w)); }

// The key's name as the script and ViewLoop::apply_key know it; "" for a key the view ignores.
const char* key_name(int key) {
    switch (key) {
        case GLFW_KEY_SPACE: return "space";
        case GLFW_KEY_LEFT: return "left";
        case GLFW_KEY_RIGHT: return "right";
        case GLFW_KEY_UP: return "up";
        case GLFW_KEY_DOWN: return "down";
        case GLFW_KEY_R: return "r";
        case GLFW_KEY_L: return "l";
        case GLFW_KEY_S: return "s";
        case GLFW_KEY_SLASH: return "?";  // '?' is shift + '/' on most layouts
        case GLFW_KEY_H: return "?";
        case GLFW_KEY_TAB: return "tab";
        default: return "";
    }
}

}  // namespace

void install_input_callbacks(GLFWwindow* w) {
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
        if (action == GLFW_RELEASE || ui_wants_keys()) return;
        Input& in = input_of(win);
        in.shift = (mods & GLFW_MOD_SHIFT) != 0;
        const std::string name = key_name(key);
        if (!name.empty()) in.keys.push_back(name);
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
        Input& in = input_of(win);
        if (action == GLFW_PRESS && ui_wants_mouse()) return;  // a click on a panel
        if (action == GLFW_PRESS) {
            in.dragging = button;
            glfwGetCursorPos(win, &in.last_x, &in.last_y);
        } else if (button == in.dragging) {
            in.dragging = -1;
        }
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
        Input& in = input_of(win);
        if (in.dragging < 0) return;
        float dx = float(x - in.last_x), dy = float(y - in.last_y);
        in.last_x = x, in.last_y = y;
        if (in.dragging == GLFW_MOUSE_BUTTON_LEFT) in.orbit_dx += dx, in.orbit_dy += dy;
        else in.pan_dx += dx, in.pan_dy += dy;
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double y) {
        if (!ui_wants_mouse()) input_of(win).scroll += float(y);
    });
}

}  // namespace pathlet::view
