// `pathlet view` (issue 10): a GLFW window (OpenGL 4.5 core) that shows a graph's first output
// live, on the same engine, plugins and scene loading as `render`. The engine adopts the
// window's context (GlContext::adopt_current), so passes run unchanged. The graph lives in a
// ViewSession (parameter changes, graph switches, hot reload with the last good graph kept),
// the panels are Dear ImGui generated from the pass declarations (view/view_panels.hpp), the
// camera and clock are view/orbit_view.hpp, and the graph and shader files are polled for
// changes (view/file_watch.hpp).
#include "args.hpp"
#include "commands.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "plugin_host.hpp"
#include "view/file_watch.hpp"
#include "view/orbit_view.hpp"
#include "view/view_panels.hpp"
#include "view/view_script.hpp"
#include "view/view_session.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <algorithm>
#include <filesystem>
#include <fstream>
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

// Closes ImGui before the window goes (declared after GlfwWindow, so destroyed before it).
struct ImGuiGuard {
    bool on = false;
    ~ImGuiGuard() {
        if (!on) return;
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
};

bool ui_wants_mouse() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse; }
bool ui_wants_keys() { return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard; }

const char* kHelp =
    "pathlet view keys:\n"
    "  left drag: orbit   right/middle drag: pan   wheel: zoom   r: reset the view\n"
    "  space: play/pause  left/right: -/+ 0.1 s (shift: 1 s)   up/down: speed x2 / /2   l: loop on/off\n"
    "  s: screenshot of the graph output   tab: hide/show the panels   ?: this help   esc: quit\n"
    "  the panels: every graph variable and pass parameter (hover for its doc and range), switch\n"
    "  graphs, 'copy as --set' (a render command that reproduces the view), per-pass timing.\n"
    "  Editing the graph file or a shader reloads it; an error keeps the last good graph running.\n";

// A camera path file holding the current camera, so `render --camera` reproduces the view.
void write_camera(const std::string& path, const Camera& c) {
    nlohmann::json k = {{"time", 0},
                        {"eye", {c.eye.x, c.eye.y, c.eye.z}},
                        {"target", {c.target.x, c.target.y, c.target.z}},
                        {"up", {c.up.x, c.up.y, c.up.z}},
                        {"fov", c.fov_y_deg}};
    const std::string tmp = path + ".tmp";
    std::ofstream(tmp) << nlohmann::json{{"keyframes", {k}}}.dump(2) << "\n";
    std::filesystem::rename(tmp, path);
}

std::string shell_quote(const std::string& s) {
    if (s.find_first_of(" '\"$#*?;&|<>()[]{}\\") == std::string::npos) return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// The render command that reproduces what the window shows (graph, overrides, time, camera).
std::string render_command(const view::ViewSession& session, double t, glm::ivec2 size, const std::string& camera_file) {
    char buf[128];
    std::snprintf(buf, sizeof buf, " --time %.3f --size %dx%d", t, size.x, size.y);
    std::string cmd = "pathlet render " + shell_quote(session.graph_path()) + buf + " --camera " + shell_quote(camera_file);
    for (const auto& s : session.sets()) cmd += " --set " + shell_quote(s);
    return cmd;
}

std::vector<std::string> shipped_graphs() {
    std::vector<std::string> out;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(std::filesystem::path(engine_share_dir()) / "graphs", ec), end;
         !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".json") out.push_back(it->path().string());
    std::sort(out.begin(), out.end());
    return out;
}

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
        if (action == GLFW_RELEASE || ui_wants_keys()) return;
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
            case GLFW_KEY_TAB: in.keys.push_back("tab"); break;
            default: break;
        }
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

int run(const std::vector<std::string>& argv) {
    Args a("view",
           "Shows a graph's first output in a window (OpenGL 4.5 core through GLFW; needs a display:\n"
           "X11, or Xvfb for tests), with panels for every graph variable and pass parameter, graph\n"
           "switching, 'copy as --set' and per-pass timing. The mouse moves the camera, the keyboard runs\n"
           "the clock (press ? in the window for the keys). Editing the graph file or one of its shaders\n"
           "reloads it (shaders are read from the build's pass folders and share/shaders; point\n"
           "PATHLET_SHADER_PATH at your source folders to edit them in place); an error keeps the last\n"
           "good graph running and shows the error. Without --time it plays the data's time span in a\n"
           "loop; with --time it starts paused there. Close the window or press Esc to quit.");
    a.positional("GRAPH", "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
        .option("time", "T", "", "start paused at this animation time in seconds (default: play from the start)")
        .option("size", "WxH", "1280x720", "window and output size in pixels")
        .multi("set", "NAME=VALUE", "override a graph variable or a pass parameter, as for render")
        .option("camera", "FILE", "", "start from this camera path's camera at the start time (as for render)")
        .option("exit-after", "N", "0", "quit after N shown frames (0: run until closed)")
        .option("screenshot", "FILE", "", "on exit, write the graph output of the last frame (PNG/EXR)")
        .option("screenshot-window", "FILE", "", "on exit, write the whole window (graph output and panels) as PNG")
        .option("screenshot-dir", "DIR", ".", "where the s key writes pathlet_view_<frame>.png (and 'copy as --set' its camera)")
        .option("script", "FILE", "", "scripted input (JSON events per frame, fixed 1/25 s clock; see view/view_script.hpp)")
        .flag("no-ui", "no panels (tab shows them)")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
    a.example("pathlet view", "the built-in phantom through variant1_lineao, playing")
        .example("pathlet view isl --time 9 --set window=3", "illuminated streamlines, paused at 9 s, 3 s pathlets")
        .example("xvfb-run -a pathlet view --exit-after 10 --screenshot shot.png", "headless, for tests");
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
    install_callbacks(win.w);  // before ImGui's, which chain to these

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    Scene scene = load_scene(a, false);
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());

    ImGuiGuard imgui;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui_ImplGlfw_InitForOpenGL(win.w, true);
    ImGui_ImplOpenGL3_Init("#version 450");
    imgui.on = true;
    bool show_ui = !a.has("no-ui");

    // The graph: compiled and set up once (as render does); changed in place afterwards.
    GpuScene gpu;
    gpu.upload(scene);
    view::ViewSession session(rt, gpu, size, graph_path, a.all("set"));
    view::FileWatch watch;
    watch.watch(session.watched_files());
    view::PanelInfo info;
    info.graphs = shipped_graphs();
    info.backend = rt.gl->renderer() + " - " + session.profiler().backend_description();
    std::string shown_error;

    view::Playback clock;
    clock.t_min = scene.lines.time_min();
    clock.t_max = scene.lines.time_max();
    clock.playing = !a.has("time");
    clock.t = a.has("time") ? std::stod(a.get("time")) : clock.t_min;
    const Camera start = a.has("camera") ? CameraPath::load(a.get("camera")).at(clock.t, scene.bounds(), size)
                                         : frame_bounds(scene.bounds(), size);
    view::OrbitView cam(start, scene.bounds(), size);
    std::fprintf(stderr, "%s", kHelp);

    Image last, last_window;
    long shown = 0;
    uint64_t index = 0;
    size_t next_event = 0;
    auto wall = std::chrono::steady_clock::now();
    auto last_poll = wall;
    while (!glfwWindowShouldClose(win.w) && (exit_after == 0 || shown < exit_after)) {
        view::PanelActions act;
        // Scripted events for this frame go through the same paths as real input.
        for (; next_event < script.size() && script[next_event].frame <= shown; ++next_event) {
            const view::ScriptEvent& e = script[next_event];
            if (!e.key.empty()) input.keys.push_back(e.key);
            if (e.button == "left") input.orbit_dx += e.dx, input.orbit_dy += e.dy;
            else if (!e.button.empty()) input.pan_dx += e.dx, input.pan_dy += e.dy;
            input.scroll += e.scroll;
            if (!e.set.empty()) act.sets.emplace_back(e.set.substr(0, e.set.find('=')), e.set.substr(e.set.find('=') + 1));
            if (!e.graph.empty()) act.switch_to = resolve_graph_path(e.graph);
            act.reload |= e.reload;
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
            else if (k == "tab") show_ui = !show_ui;
            else if (k == "?") std::fprintf(stdout, "%s", kHelp);
        }
        if (input.orbit_dx != 0 || input.orbit_dy != 0) cam.orbit(input.orbit_dx, input.orbit_dy);
        if (input.pan_dx != 0 || input.pan_dy != 0) cam.pan(input.pan_dx, input.pan_dy);
        if (input.scroll != 0) cam.zoom(input.scroll);
        input.orbit_dx = input.orbit_dy = input.pan_dx = input.pan_dy = input.scroll = 0;

        // The panels of the previous frame asked for these; they apply before this frame runs.
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (show_ui) view::draw_panels(session, clock, info, act);
        // Hot reload: the graph and shader files, polled twice a second (every 12 frames when scripted).
        const auto now_poll = std::chrono::steady_clock::now();
        if (scripted ? shown % 12 == 0 : now_poll - last_poll > std::chrono::milliseconds(500)) {
            last_poll = now_poll;
            const auto changed = watch.changed();
            if (!changed.empty()) {
                std::fprintf(stderr, "view: %s changed, reloading\n", changed.front().c_str());
                act.reload = true;
            }
        }
        for (const auto& [name, value] : act.sets) session.set(name, value);
        if (!act.switch_to.empty()) session.switch_graph(act.switch_to);
        if (act.reload) session.rebuild();
        if (!act.sets.empty() || !act.switch_to.empty() || act.reload) watch.watch(session.watched_files());
        if (act.reset_view) cam.reset();
        if (session.error() != shown_error) {
            shown_error = session.error();
            if (!shown_error.empty()) std::fprintf(stderr, "view: error (still showing the last good graph):\n%s\n", shown_error.c_str());
            else std::fprintf(stderr, "view: the graph works again\n");
        }
        if (act.copy_command) {
            const std::string camera_file = (std::filesystem::path(a.get("screenshot-dir")) / "pathlet_view_camera.json").string();
            write_camera(camera_file, cam.camera());
            info.command = render_command(session, clock.t, size, camera_file);
            glfwSetClipboardString(win.w, info.command.c_str());
            std::fprintf(stdout, "%s\n", info.command.c_str());
        }

        auto t0 = std::chrono::steady_clock::now();
        Executor& exec = session.executor();
        exec.run_frame({index++, clock.t, cam.camera()});
        Texture tex = exec.texture(session.compiled().outputs.front().resource);
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex.id, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glViewport(0, 0, size.x, size.y);
        glClearColor(1, 1, 1, 1);  // an output with a transparent background shows on white
        glClear(GL_COLOR_BUFFER_BIT);
        glBlitNamedFramebuffer(fbo, 0, 0, 0, tex.width, tex.height, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT,
                               GL_NEAREST);
        glDeleteFramebuffers(1, &fbo);
        if (a.has("screenshot") || screenshot_now) last = read_texture(tex.id, tex.width, tex.height, 0, 4);
        info.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (a.has("screenshot-window")) {
            last_window.width = size.x, last_window.height = size.y, last_window.channels = 4;
            std::vector<uint8_t> px(size_t(size.x) * size_t(size.y) * 4);
            glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
            last_window.pixels.resize(px.size());
            for (int y = 0; y < size.y; ++y)  // GL rows are bottom-up
                for (size_t x = 0; x < size_t(size.x) * 4; ++x)
                    last_window.pixels[size_t(y) * size_t(size.x) * 4 + x] =
                        float(px[size_t(size.y - 1 - y) * size_t(size.x) * 4 + x]) / 255.0f;
        }
        if (screenshot_now) {
            char name[64];
            std::snprintf(name, sizeof name, "pathlet_view_%05ld.png", shown);
            const std::string path = (std::filesystem::path(a.get("screenshot-dir")) / name).string();
            write_image(path, last);
            std::fprintf(stderr, "screenshot: %s\n", path.c_str());
        }
        // Per-pass timing bars: medians of the last 30 frames, then the profiler starts afresh
        // (bounded memory over an afternoon).
        Profiler& prof = session.profiler();
        if (prof.frames_recorded() >= 30) {
            prof.flush();
            info.timing.clear();
            for (const auto& p : prof.passes()) info.timing.push_back({p.name, p.gpu_ms.median});
            info.backend = rt.gl->renderer() + " - " + prof.backend_description();
            prof.init(prof.backend(), rt.gl->renderer());
            prof.set_warmup_frames(0);
        }
        double window = 0.0;  // for the title
        for (const auto& v : session.graph().variables)
            if (v.name == "window" && v.value.is_number()) window = v.value.get<double>();
        char title[256];
        std::snprintf(title, sizeof title, "pathlet view - %s - t = %.2f s (window %.2g s) x%.3g %s%s - %.0f ms",
                      graph_display_name(session.graph()).c_str(), clock.t, window, clock.speed,
                      clock.playing ? "playing" : "paused", clock.loop ? ", loop" : "", info.frame_ms);
        glfwSetWindowTitle(win.w, title);
        glfwSwapBuffers(win.w);
        glfwPollEvents();
        if (glfwGetKey(win.w, GLFW_KEY_ESCAPE) == GLFW_PRESS && !ui_wants_keys()) break;
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
    if (a.has("screenshot-window")) {
        if (last_window.width == 0) throw std::runtime_error("view: no frame was shown; no window screenshot written");
        write_image(a.get("screenshot-window"), last_window);
        std::fprintf(stderr, "window screenshot: %s\n", a.get("screenshot-window").c_str());
    }
    if (scripted && !session.error().empty()) return 1;  // a script whose last change failed
    return 0;
}

PATHLET_COMMAND("view", "show a graph's output live in a window: camera, clock, parameter panels, hot reload", run);

}  // namespace
}  // namespace pathlet::cli
