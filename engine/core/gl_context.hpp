// Headless OpenGL 4.5 core through EGL: the device platform first (a real GPU), Mesa's
// surfaceless platform second. No default framebuffer: passes render into FBOs.
#pragma once

#include <pathlet/gl.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

struct GlError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class GlContext {
public:
    struct Options {
        bool debug = false;     // KHR_debug context; messages are captured either way
        int device_index = -1;  // EGL device to use (-1: first hardware device); env PATHLET_EGL_DEVICE
    };
    // Throws GlError saying what was tried when no context can be made.
    static std::unique_ptr<GlContext> create_headless(const Options& opts);
    static std::unique_ptr<GlContext> create_headless() { return create_headless(Options{}); }
    // Wraps the 4.5 core context the caller made current (a GLFW window of `pathlet view`):
    // same error capture as headless, but the caller owns and destroys the context.
    // Throws GlError when no context is current or it is older than 4.5.
    static std::unique_ptr<GlContext> adopt_current(const std::string& platform);
    ~GlContext();

    std::string renderer() const;  // GL_RENDERER
    std::string version() const;   // GL_VERSION
    std::string vendor() const;
    const std::string& platform() const { return platform_; }  // "EGL device 0 (...)" / "EGL surfaceless"
    bool is_software() const;      // llvmpipe / softpipe / SwiftShader
    std::string summary() const;   // one line for logs

    // KHR_debug messages of type ERROR (or severity HIGH) since the last call.
    std::vector<std::string> take_errors();
    // True when the debug callback has recorded an error since the last take_errors().
    bool has_errors() const { return has_errors_.load(std::memory_order_relaxed); }
    // Current debug group label (the executor sets the pass name), prefixed to messages.
    void set_scope(const std::string& scope);

private:
    GlContext() = default;
    static void debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                               const GLchar* message, const void* user);
    static void install_debug_output(GlContext* self);
    void* display_ = nullptr;
    bool adopted_ = false;
    void* context_ = nullptr;
    std::string platform_;
    std::string scope_;
    std::mutex mu_;
    std::vector<std::string> errors_;
    std::atomic<bool> has_errors_{false};
};

}  // namespace pathlet
