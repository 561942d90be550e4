// The viewer's window: GLFW (an OpenGL 4.5 core context) and Dear ImGui over it, closed in
// reverse order of opening.
#pragma once

#include <glm/glm.hpp>

struct GLFWwindow;

namespace pathlet::view {

class Window {
public:
    Window() = default;
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // The GL context is current afterwards. `user` receives the input callbacks' events
    // (install_callbacks runs before ImGui's, which chain to them).
    void open(glm::ivec2 size, bool vsync, void* user, void (*install_callbacks)(GLFWwindow*));
    // Dear ImGui over the window (after the engine adopted its context).
    void open_ui();
    GLFWwindow* get() const { return w_; }

private:
    GLFWwindow* w_ = nullptr;
    bool glfw_ = false, imgui_ = false;
};

// Whether the panels take the mouse or the keys this frame (then the view does not).
bool ui_wants_mouse();
bool ui_wants_keys();

}  // namespace pathlet::view
