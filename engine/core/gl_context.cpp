#include "gl_context.hpp"

#include <pathlet/pass.hpp>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace pathlet {

namespace {

bool has_ext(const char* list, const char* ext) {
    if (!list) return false;
    size_t n = std::strlen(ext);
    for (const char* p = std::strstr(list, ext); p; p = std::strstr(p + 1, ext))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

const char* egl_error_name(EGLint e) {
    switch (e) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error";
    }
}

// Initialises a display and makes a 4.5 core context current on it; returns the context or null.
EGLContext make_context(EGLDisplay dpy, bool debug, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) {
        why = std::string("eglInitialize failed: ") + egl_error_name(eglGetError());
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed";
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
    EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR
    if (!has_ext(exts, "EGL_KHR_no_config_context")) {
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, attribs, &config, 1, &n) || n < 1) {
            why = "no EGL config with OpenGL and pbuffer support";
            eglTerminate(dpy);
            return EGL_NO_CONTEXT;
        }
    }
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx == EGL_NO_CONTEXT) {
        why = std::string("eglCreateContext(OpenGL 4.5 core) failed: ") + egl_error_name(eglGetError());
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    EGLSurface surface = EGL_NO_SURFACE;
    if (!has_ext(exts, "EGL_KHR_surfaceless_context")) {
        const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surface = eglCreatePbufferSurface(dpy, config, pb);
    }
    if (!eglMakeCurrent(dpy, surface, surface, ctx)) {
        why = std::string("eglMakeCurrent failed: ") + egl_error_name(eglGetError());
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        return EGL_NO_CONTEXT;
    }
    return ctx;
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create_headless(const Options& opts) {
    std::unique_ptr<GlContext> self(new GlContext());
    bool debug = opts.debug || std::getenv("PATHLET_GL_DEBUG");
    int want_device = opts.device_index;
    if (const char* e = std::getenv("PATHLET_EGL_DEVICE")) want_device = std::atoi(e);

    const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    std::string tried;
    bool force_software = std::getenv("LIBGL_ALWAYS_SOFTWARE") != nullptr;

    // 1. Device platform: a hardware device unless one is named or software is forced.
    if (get_platform_display && query_devices && has_ext(client_exts, "EGL_EXT_platform_device") && !force_software) {
        EGLDeviceEXT devices[16];
        EGLint n = 0;
        if (query_devices(16, devices, &n) && n > 0) {
            for (EGLint i = 0; i < n; ++i) {
                const char* dev_exts = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
                bool software = has_ext(dev_exts, "EGL_MESA_device_software");
                if (want_device >= 0 ? i != want_device : software) continue;
                EGLDisplay dpy = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (dpy == EGL_NO_DISPLAY) continue;
                std::string why;
                EGLContext ctx = make_context(dpy, debug, why);
                if (ctx != EGL_NO_CONTEXT) {
                    self->display_ = dpy;
                    self->context_ = ctx;
                    self->platform_ = "EGL device " + std::to_string(i);
                    break;
                }
                tried += "  EGL device " + std::to_string(i) + ": " + why + "\n";
            }
        } else {
            tried += "  EGL device platform: no devices\n";
        }
    }
    else if (!force_software)
        tried += "  EGL device platform: not offered by this EGL (no EGL_EXT_platform_device; no vendor library?)\n";
    // 2. Mesa surfaceless (llvmpipe when there is no GPU).
    if (!self->context_ && !(get_platform_display && has_ext(client_exts, "EGL_MESA_platform_surfaceless")))
        tried += "  EGL surfaceless: not offered by this EGL (no EGL_MESA_platform_surfaceless; is Mesa's EGL installed?)\n";
    if (!self->context_ && get_platform_display && has_ext(client_exts, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        std::string why = "no display";
        EGLContext ctx = dpy != EGL_NO_DISPLAY ? make_context(dpy, debug, why) : EGL_NO_CONTEXT;
        if (ctx != EGL_NO_CONTEXT) {
            self->display_ = dpy;
            self->context_ = ctx;
            self->platform_ = "EGL surfaceless";
        } else {
            tried += "  EGL surfaceless: " + why + "\n";
        }
    }
    if (!self->context_)
        throw GlError("cannot create a headless OpenGL 4.5 context. Tried:\n" + tried +
                      "Install Mesa (apt-get install libegl-mesa0 libgl1-mesa-dri) or a GPU driver with EGL.");

    install_debug_output(self.get());
    return self;
}

void GlContext::install_debug_output(GlContext* self) {
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous output pins a message to the call that caused it, and costs a GPU driver
    // CPU time on every call (it may not defer work): only with PATHLET_GL_DEBUG. Without it a
    // driver may report later, from its own thread (the callback locks); Mesa reports at the
    // call either way. An error is still caught in the frame it happens.
    if (std::getenv("PATHLET_GL_DEBUG")) glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    else glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(&GlContext::debug_callback, self);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    // Notifications are chatty (buffer placement hints); keep errors, warnings, performance.
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
}

std::unique_ptr<GlContext> GlContext::adopt_current(const std::string& platform) {
    // glvnd dispatches libOpenGL calls to whichever context (GLX or EGL) is current.
    const GLubyte* version = glGetString(GL_VERSION);
    if (!version)
        throw GlError("no OpenGL context is current (" + platform + ")");
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw GlError("the " + platform + " context is OpenGL " + reinterpret_cast<const char*>(version) +
                      "; Pathlet needs 4.5 core");
    auto self = std::unique_ptr<GlContext>(new GlContext());
    self->platform_ = platform;
    self->adopted_ = true;
    install_debug_output(self.get());
    return self;
}

void GlContext::debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei length, const GLchar* message,
                               const void* user) {
    auto* self = const_cast<GlContext*>(static_cast<const GlContext*>(user));
    std::string msg(message, length > 0 ? size_t(length) : std::strlen(message));
    std::lock_guard<std::mutex> lock(self->mu_);
    std::string where = self->scope_.empty() ? "" : "[" + self->scope_ + "] ";
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
        self->errors_.push_back(where + msg);
        self->has_errors_ = true;
    } else if (severity == GL_DEBUG_SEVERITY_MEDIUM && std::getenv("PATHLET_GL_DEBUG")) {
        std::fprintf(stderr, "GL warning: %s%s\n", where.c_str(), msg.c_str());
    }
}

GlContext::~GlContext() {
    if (display_) {
        glDebugMessageCallback(nullptr, nullptr);
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        // No eglTerminate: Mesa leaks a driver allocation there that confuses LeakSanitizer,
        // and the display is reused by later contexts in the same process anyway.
    } else if (adopted_) {
        glDebugMessageCallback(nullptr, nullptr);  // the owner destroys the context itself
    }
}

static std::string gl_string(GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? reinterpret_cast<const char*>(s) : "";
}

std::string GlContext::renderer() const { return gl_string(GL_RENDERER); }
std::string GlContext::version() const { return gl_string(GL_VERSION); }
std::string GlContext::vendor() const { return gl_string(GL_VENDOR); }

bool GlContext::is_software() const { return !software_rasterizer(renderer()).empty(); }

std::string GlContext::summary() const {
    return "GL renderer: " + renderer() + " | " + version() + " | " + platform_;
}

std::vector<std::string> GlContext::take_errors() {
    std::lock_guard<std::mutex> lock(mu_);
    std::vector<std::string> out;
    out.swap(errors_);
    has_errors_ = false;
    // Errors that reached no callback (should not happen with a debug context) still count.
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "glGetError 0x%04x", e);
        out.push_back((scope_.empty() ? "" : "[" + scope_ + "] ") + buf);
    }
    return out;
}

void GlContext::set_scope(const std::string& scope) {
    std::lock_guard<std::mutex> lock(mu_);
    scope_.assign(scope);  // reuses capacity: called per pass per frame
}

}  // namespace pathlet
