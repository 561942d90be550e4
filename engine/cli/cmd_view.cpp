// `pathlet view` (issue 10): a GLFW window (OpenGL 4.5 core) that shows a graph's first output
// live, on the same engine, plugins and scene loading as `render`. The engine adopts the
// window's context (GlContext::adopt_current), so passes run unchanged; the graph is compiled
// and its executor set up once, then every shown frame runs it with the mouse camera and the
// playback clock (view/orbit_view.hpp). Not yet: ImGui panels, hot reload, timing bars.
#include "args.hpp"
#include "commands.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "view/orbit_view.hpp"
#include "view/view_script.hpp"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>

namespace pathlet::cli {
namespace {

struct GlfwWindow {
    GLFWwindow* w = nullptr;
    ~GlfwWindow() {
        if (w) glfwDestroyWindow(w);
        glfwTerminate();
    }
};

const char* kHelp =
    "pathlet view keys:\n"
    "  left drag: orbit   right/middle drag: pan   wheel: zoom   r: reset the view\n"
    "  space: play/pause  left/right: -/+ 0.1 s (shift: 1 s)   up/down: speed x2 / /2   l: loop on/off\n"
    "  s: screenshot of the graph output   ?: this help   esc: quit\n";

// Input as the window delivers it, applied once per shown frame (the script feeds the same).
struct Input {
    std::deque<std::string> keys;
    bool shift = false;
    float orbit_dx = 0, orbit_dy = 0, pan_dx = 0, pan_dy = 0, scroll = 0;
    double last_x = 0, last_y = 0;
    int dragging = -1;  // GLFW mouse button held, -1 none
};

Input& input_of(GLFWwindow* w) { return *static_cast<Input*>(glfwGetWindowUserPointer(w)); }

void install_callbacks(GLFWwindow* w) {
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
        if (action == GLFW_RELEASE) return;
        Input& in = input_of(win);
        in.shift = (mods & GLFW_MOD_SHIFT) != 0;
        switch (key) {
            case GLFW_KEY_SPACE: in.keys.push_back("space"); break;
            case GLFW_KEY_LEFT: in.keys.push_back("left"); break;
            case GLFW_KEY_RIGHT: in.keys.push_back("right"); break;
            case GLFW_KEY_UP: in.keys.push_back("up"); break;
            case GLFW_KEY_DOWN: in.keys.push_back("down"); break;
            case GLFW_KEY_R: in.keys.push_back("r"); break;
            case GLFW_KEY_L: in.keys.push_back("l"); break;
            case GLFW_KEY_S: in.keys.push_back("s"); break;
            case GLFW_KEY_SLASH: in.keys.push_back("?"); break;  // '?' is shift + '/' on most layouts
            case GLFW_KEY_H: in.keys.push_back("?"); break;
            default: break;
        }
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
        Input& in = input_of(win);
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
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double y) { input_of(win).scroll += float(y); });
}

int run(const std::vector<std::string>& argv) {
    Args a("view",
           "Shows a graph's first output in a window (OpenGL 4.5 core through GLFW; needs a display:\n"
           "X11, or Xvfb for tests). The mouse moves the camera, the keyboard runs the clock (press ?\n"
           "in the window for the keys). Without --time it plays the data's time span in a loop;\n"
           "with --time it starts paused there. Close the window or press Esc to quit.");
    a.positional("GRAPH", "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
        .option("time", "T", "", "start paused at this animation time in seconds (default: play from the start)")
        .option("size", "WxH", "1280x720", "window and output size in pixels")
        .multi("set", "NAME=VALUE", "override a graph variable or a pass parameter, as for render")
        .option("camera", "FILE", "", "start from this camera path's camera at the start time (as for render)")
        .option("exit-after", "N", "0", "quit after N shown frames (0: run until closed)")
        .option("screenshot", "FILE", "", "on exit, write the graph output of the last frame (PNG/EXR)")
        .option("screenshot-dir", "DIR", ".", "where the s key writes pathlet_view_<frame>.png")
        .option("script", "FILE", "", "scripted input (JSON events per frame, fixed 1/25 s clock; see view/view_script.hpp)")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
    if (!a.parse(argv)) return 0;

    std::string graph_path;
    glm::ivec2 size;
    try {
        graph_path = resolve_graph_path(a.pos("GRAPH").empty() ? "variant1_lineao" : a.pos("GRAPH"));
        size = parse_size(a.get("size"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    long exit_after = a.integer("exit-after");
    if (exit_after < 0) throw UsageError("--exit-after must be >= 0");
    std::vector<view::ScriptEvent> script;
    if (a.has("script")) script = view::load_script(a.get("script"));
    const bool scripted = a.has("script");

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
    win.w = glfwCreateWindow(size.x, size.y, "pathlet view", nullptr, nullptr);
    if (!win.w) throw std::runtime_error("view: the display offers no OpenGL 4.5 core window");
    glfwMakeContextCurrent(win.w);
    glfwSwapInterval(scripted ? 0 : 1);
    Input input;
    glfwSetWindowUserPointer(win.w, &input);
    install_callbacks(win.w);

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    Scene scene = load_scene(a, false);
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());

    // The graph, compiled and set up once (as render does), then run every shown frame.
    const GraphFile g = rt.load_graph(graph_path, a.all("set"));
    const CompiledGraph cg = compile_graph(g, rt.registry, size);
    if (cg.outputs.empty()) throw std::runtime_error(graph_path + ": the graph has no output to show");
    GpuScene gpu;
    gpu.upload(scene);
    Executor exec(*rt.gl, cg, gpu);
    exec.setup();
    const std::string gname = graph_display_name(g);
    double window = 0.0;  // for the title
    for (const auto& v : g.variables)
        if (v.name == "window" && v.value.is_number()) window = v.value.get<double>();

    view::Playback clock;
    clock.t_min = scene.lines.time_min();
    clock.t_max = scene.lines.time_max();
    clock.playing = !a.has("time");
    clock.t = a.has("time") ? std::stod(a.get("time")) : clock.t_min;
    const Camera start = a.has("camera") ? CameraPath::load(a.get("camera")).at(clock.t, scene.bounds(), size)
                                         : frame_bounds(scene.bounds(), size);
    view::OrbitView cam(start, scene.bounds(), size);
    std::fprintf(stderr, "%s", kHelp);

    Image last;
    long shown = 0;
    uint64_t index = 0;
    size_t next_event = 0;
    auto wall = std::chrono::steady_clock::now();
    double frame_ms = 0;
    while (!glfwWindowShouldClose(win.w) && (exit_after == 0 || shown < exit_after)) {
        // Scripted events for this frame go through the same queue as real input.
        for (; next_event < script.size() && script[next_event].frame <= shown; ++next_event) {
            const view::ScriptEvent& e = script[next_event];
            if (!e.key.empty()) input.keys.push_back(e.key);
            if (e.button == "left") input.orbit_dx += e.dx, input.orbit_dy += e.dy;
            else if (!e.button.empty()) input.pan_dx += e.dx, input.pan_dy += e.dy;
            input.scroll += e.scroll;
        }
        bool screenshot_now = false;
        for (; !input.keys.empty(); input.keys.pop_front()) {
            const std::string& k = input.keys.front();
            const double step = input.shift ? 1.0 : 0.1;
            if (k == "space") clock.playing = !clock.playing;
            else if (k == "left") clock.scrub(-step);
            else if (k == "right") clock.scrub(step);
            else if (k == "up") clock.speed *= 2.0;
            else if (k == "down") clock.speed *= 0.5;
            else if (k == "l") clock.loop = !clock.loop;
            else if (k == "r") cam.reset();
            else if (k == "s") screenshot_now = true;
            else if (k == "?") std::fprintf(stdout, "%s", kHelp);
        }
        if (input.orbit_dx != 0 || input.orbit_dy != 0) cam.orbit(input.orbit_dx, input.orbit_dy);
        if (input.pan_dx != 0 || input.pan_dy != 0) cam.pan(input.pan_dx, input.pan_dy);
        if (input.scroll != 0) cam.zoom(input.scroll);
        input.orbit_dx = input.orbit_dy = input.pan_dx = input.pan_dy = input.scroll = 0;

        auto t0 = std::chrono::steady_clock::now();
        exec.run_frame({index++, clock.t, cam.camera()});
        Texture tex = exec.texture(cg.outputs.front().resource);
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex.id, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glClearColor(1, 1, 1, 1);  // the output's background is transparent: show it on white
        glClear(GL_COLOR_BUFFER_BIT);
        glBlitNamedFramebuffer(fbo, 0, 0, 0, tex.width, tex.height, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT,
                               GL_NEAREST);
        glDeleteFramebuffers(1, &fbo);
        if (a.has("screenshot") || screenshot_now) last = read_texture(tex.id, tex.width, tex.height, 0, 4);
        frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (screenshot_now) {
            char name[64];
            std::snprintf(name, sizeof name, "pathlet_view_%05ld.png", shown);
            const std::string path = (std::filesystem::path(a.get("screenshot-dir")) / name).string();
            write_image(path, last);
            std::fprintf(stderr, "screenshot: %s\n", path.c_str());
        }
        char title[256];
        std::snprintf(title, sizeof title, "pathlet view - %s - t = %.2f s (window %.2g s) x%.3g %s%s - %.0f ms", gname.c_str(),
                      clock.t, window, clock.speed, clock.playing ? "playing" : "paused", clock.loop ? ", loop" : "",
                      frame_ms);
        glfwSetWindowTitle(win.w, title);
        glfwSwapBuffers(win.w);
        glfwPollEvents();
        if (glfwGetKey(win.w, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        auto now = std::chrono::steady_clock::now();
        clock.advance(scripted ? 0.04 : std::chrono::duration<double>(now - wall).count());
        wall = now;
        ++shown;
    }
    if (a.has("screenshot")) {
        if (last.width == 0) throw std::runtime_error("view: no frame was shown; no screenshot written");
        write_image(a.get("screenshot"), last);
        std::fprintf(stderr, "screenshot: %s\n", a.get("screenshot").c_str());
    }
    return 0;
}

PATHLET_COMMAND("view", "show a graph's output live in a window: mouse camera, play/pause/scrub (no panels yet)", run);

}  // namespace
}  // namespace pathlet::cli
