#include "view/view_window.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace pathlet::view {

Window::~Window() {
    if (imgui_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (w_) glfwDestroyWindow(w_);
    if (glfw_) glfwTerminate();
}

void Window::open(glm::ivec2 size, bool vsync, void* user, void (*install_callbacks)(GLFWwindow*)) {
    glfw_ = glfwInit();
    if (!glfw_)
        throw std::runtime_error("view: cannot open a window: no display (DISPLAY is '" +
                                 std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") +
                                 "'). Run it on a desktop, or under Xvfb: xvfb-run pathlet view ...");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    w_ = glfwCreateWindow(size.x, size.y, "pathlet view", nullptr, nullptr);
    if (!w_) throw std::runtime_error("view: the display offers no OpenGL 4.5 core window");
    glfwMakeContextCurrent(w_);
    glfwSwapInterval(vsync ? 1 : 0);
    glfwSetWindowUserPointer(w_, user);
    install_callbacks(w_);  // before ImGui's, which chain to these
}

void Window::open_ui() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui_ImplGlfw_InitForOpenGL(w_, true);
    ImGui_ImplOpenGL3_Init("#version 450");
    imgui_ = true;
}

bool ui_wants_mouse() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse; }
bool ui_wants_keys() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace pathlet::view
