// `pathlet view` (issue 10), first cut: a GLFW window (OpenGL 4.5 core) that shows a graph's
// first output live, on the same engine, plugins and scene loading as `render`. The engine
// adopts the window's context (GlContext::adopt_current), so passes run unchanged.
// Not yet: mouse camera, time controls, ImGui panels, hot reload, scripted input.
#include "args.hpp"
#include "commands.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"

#include <GLFW/glfw3.h>

#include <cstdio>

namespace pathlet::cli {
namespace {

struct GlfwWindow {
    GLFWwindow* w = nullptr;
    ~GlfwWindow() {
        if (w) glfwDestroyWindow(w);
        glfwTerminate();
    }
};

int run(const std::vector<std::string>& argv) {
    Args a("view",
           "Shows a graph's first output in a window (OpenGL 4.5 core through GLFW; needs a display:\n"
           "X11, or Xvfb for tests). Close the window or press Esc to quit.");
    a.positional("GRAPH", "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
        .option("time", "T", "", "animation time in seconds (default: the middle of the data's time span)")
        .option("size", "WxH", "1280x720", "window and output size in pixels")
        .multi("set", "NAME=VALUE", "override a graph variable or a pass parameter, as for render")
        .option("camera", "FILE", "", "camera path JSON, as for render")
        .option("exit-after", "N", "0", "quit after N shown frames (0: run until closed)")
        .option("screenshot", "FILE", "", "on exit, write the graph output of the last frame (PNG/EXR)")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
    if (!a.parse(argv)) return 0;

    RenderOptions opt;
    try {
        opt.graph_path = resolve_graph_path(a.pos("GRAPH").empty() ? "variant1_lineao" : a.pos("GRAPH"));
        opt.size = parse_size(a.get("size"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    long exit_after = a.integer("exit-after");
    if (exit_after < 0) throw UsageError("--exit-after must be >= 0");
    opt.sets = a.all("set");
    opt.camera_path = a.get("camera");
    opt.write_images = false;
    opt.quiet = true;
    opt.warmup = 0;

    GlfwWindow win;
    if (!glfwInit())
        throw std::runtime_error("view: cannot open a window: no display (DISPLAY is '" +
                                 std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") +
                                 "'). Run it on a desktop, or under Xvfb: xvfb-run pathlet view ...");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    win.w = glfwCreateWindow(opt.size.x, opt.size.y, "pathlet view", nullptr, nullptr);
    if (!win.w) throw std::runtime_error("view: the display offers no OpenGL 4.5 core window");
    glfwMakeContextCurrent(win.w);
    glfwSwapInterval(1);

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    Scene scene = load_scene(a, false);
    double t = a.has("time") ? std::stod(a.get("time")) : 0.5 * (scene.lines.time_min() + scene.lines.time_max());
    opt.time = {t, t, 1.0};
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());

    Image last;
    long shown = 0;
    // Each round renders one frame through render() (the same compile/execute path) and
    // blits its first output into the window.
    while (!glfwWindowShouldClose(win.w) && (exit_after == 0 || shown < exit_after)) {
        render(rt, scene, opt, [&](const Executor& exec, size_t) {
            const CompiledGraph& cg = exec.graph();
            if (cg.outputs.empty()) return;
            Texture tex = exec.texture(cg.outputs.front().resource);
            GLuint fbo = 0;
            glCreateFramebuffers(1, &fbo);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex.id, 0);
            glBlitNamedFramebuffer(fbo, 0, 0, 0, tex.width, tex.height, 0, 0, opt.size.x, opt.size.y,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glDeleteFramebuffers(1, &fbo);
            if (a.has("screenshot")) last = read_texture(tex.id, tex.width, tex.height, 0, 4);
        });
        glfwSwapBuffers(win.w);
        glfwPollEvents();
        if (glfwGetKey(win.w, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        ++shown;
    }
    if (a.has("screenshot")) {
        if (last.width == 0) throw std::runtime_error("view: no frame was shown; no screenshot written");
        write_image(a.get("screenshot"), last);
        std::fprintf(stderr, "screenshot: %s\n", a.get("screenshot").c_str());
    }
    return 0;
}

PATHLET_COMMAND("view", "show a graph's output live in a window (first cut: no panels yet)", run);

}  // namespace
}  // namespace pathlet::cli
