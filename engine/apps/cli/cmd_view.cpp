// `pathlet view` (issue 10): a GLFW window (OpenGL 4.5 core) that shows a graph's first output
// live, on the same engine, plugins and scene loading as `render`. The engine adopts the
// window's context (GlContext::adopt_current), so passes run unchanged. The graph lives in a
// ViewSession (parameter changes, graph switches, hot reload with the last good graph kept),
// the panels are Dear ImGui generated from the pass declarations (view/view_panels.hpp), the
// camera and clock are view/orbit_view.hpp, and the graph and shader files are polled for
// changes (view/file_watch.hpp). Each shown frame is three steps of ViewLoop: input (window
// and script events into the clock, camera and actions), frame (panels, hot reload, the
// actions, then the graph) and present (the output and panels on the window, screenshots).
#include "commands.hpp"
#include "common_options.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "pixel_store.hpp"
#include "plugin_host.hpp"
#include "renderer.hpp"
#include "util/atomic_file.hpp"
#include "util/text.hpp"
#include "view/file_watch.hpp"
#include "view/orbit_view.hpp"
#include "view/view_panels.hpp"
#include "view/view_script.hpp"
#include "view/view_session.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>

namespace pathlet::cli {
namespace {

struct ViewOptions {
    std::string graph = "variant1_lineao", camera, screenshot, screenshot_window, screenshot_dir = ".", script;
    std::optional<double> time;
    glm::ivec2 size{1280, 720};
    std::vector<std::string> sets;
    long exit_after = 0;
    bool no_ui = false, allow_empty = false;
    PluginOptions plugins;
    SceneOptions data;

    void declare(Args& a) {
        a.positional("GRAPH", graph, "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
            .option("time", time, "T", "start paused at this animation time in seconds (default: play from the start)")
            .flag("allow-empty-frames", allow_empty,
                  "start at the --time asked for even where it lies outside the data's time span (an empty frame); "
                  "without it such a time is an error naming the span");
        declare_size(a, size, "window and output size in pixels");
        declare_sets(a, sets);
        declare_camera(a, camera);
        a.option("exit-after", exit_after, "N", "quit after N shown frames (0: run until closed)")
            .option("screenshot", screenshot, "FILE", "on exit, write the graph output of the last frame (PNG/EXR)")
            .option("screenshot-window", screenshot_window, "FILE", "on exit, write the whole window (graph output and panels) as PNG")
            .option("screenshot-dir", screenshot_dir, "DIR",
                    "where the s key writes pathlet_view_<frame>.png (and 'copy as --set' its camera)")
            .option("script", script, "FILE", "scripted input (JSON events per frame, fixed 1/25 s clock; see view/view_script.hpp)")
            .flag("no-ui", no_ui, "no panels (tab shows them)");
        plugins.declare(a);
        data.declare(a);
    }
};

// The window and Dear ImGui, closed in reverse order of opening.
class Window {
public:
    ~Window() {
        if (imgui_) {
            ImGui_ImplOpenGL3_Shutdown();
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
        if (w_) glfwDestroyWindow(w_);
        if (glfw_) glfwTerminate();
    }
    // The GL context is current afterwards. `user` receives the input callbacks' events.
    void open(glm::ivec2 size, bool vsync, void* user, void (*install_callbacks)(GLFWwindow*));
    // Dear ImGui over the window (after the engine adopted its context).
    void open_ui();
    GLFWwindow* get() const { return w_; }

private:
    GLFWwindow* w_ = nullptr;
    bool glfw_ = false, imgui_ = false;
};

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
    write_file_atomic(path, nlohmann::json{{"keyframes", {k}}}.dump(2) + "\n");
}

// The render command that reproduces what the window shows (graph, overrides, time, camera).
std::string render_command(const view::ViewSession& session, double t, glm::ivec2 size, const std::string& camera_file) {
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", t);
    std::vector<std::string> words = {"pathlet", "render", session.graph_path(), "--time", time,
                                      "--size", std::to_string(size.x) + "x" + std::to_string(size.y),
                                      "--camera", camera_file};
    for (const auto& s : session.sets()) words.insert(words.end(), {"--set", s});
    return text::shell_command(words);
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

// The graph output on the window's framebuffer. Its read framebuffer is made once and kept;
// each frame attaches the output texture (a rebuilt graph may bring another texture).
class OutputBlit {
public:
    OutputBlit() { glCreateFramebuffers(1, &fbo_); }
    ~OutputBlit() { glDeleteFramebuffers(1, &fbo_); }
    OutputBlit(const OutputBlit&) = delete;
    OutputBlit& operator=(const OutputBlit&) = delete;
    void draw(const Texture& tex, glm::ivec2 window) const {
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex.id, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glViewport(0, 0, window.x, window.y);
        glClearColor(1, 1, 1, 1);  // an output with a transparent background shows on white
        glClear(GL_COLOR_BUFFER_BIT);
        glBlitNamedFramebuffer(fbo_, 0, 0, 0, tex.width, tex.height, 0, 0, window.x, window.y, GL_COLOR_BUFFER_BIT,
                               GL_NEAREST);
    }

private:
    GLuint fbo_ = 0;
};

// The whole window (output and panels) for --screenshot-window, kept on the GPU: the window's
// pixels are gone after the swap and closing it comes unannounced, so each frame is blitted
// into a texture (no read-back, no wait) and only the last one is read, once, at the end.
class WindowCopy {
public:
    WindowCopy() = default;
    ~WindowCopy() {
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
        if (tex_) glDeleteTextures(1, &tex_);
    }
    WindowCopy(const WindowCopy&) = delete;
    WindowCopy& operator=(const WindowCopy&) = delete;
    void copy(glm::ivec2 size) {
        if (size != size_) {
            if (fbo_) glDeleteFramebuffers(1, &fbo_);
            if (tex_) glDeleteTextures(1, &tex_);
            glCreateTextures(GL_TEXTURE_2D, 1, &tex_);
            glTextureStorage2D(tex_, 1, GL_RGBA8, size.x, size.y);
            glCreateFramebuffers(1, &fbo_);
            glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex_, 0);
            size_ = size;
        }
        glDisable(GL_SCISSOR_TEST);  // a blit is scissored (glReadPixels was not)
        glBlitNamedFramebuffer(0, fbo_, 0, 0, size.x, size.y, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    bool empty() const { return tex_ == 0; }
    // Top row first, bytes / 255 as glReadPixels of the window gave them.
    Image read() const {
        Image img;
        img.width = size_.x, img.height = size_.y, img.channels = 4;
        const size_t row = size_t(size_.x) * 4;
        std::vector<uint8_t> px(row * size_t(size_.y));
        {
            const PlainPixelStore plain(PlainPixelStore::pack);
            glGetTextureImage(tex_, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
        }
        img.pixels.resize(px.size());
        for (int y = 0; y < size_.y; ++y)  // GL rows are bottom-up
            for (size_t x = 0; x < row; ++x)
                img.pixels[size_t(y) * row + x] = float(px[size_t(size_.y - 1 - y) * row + x]) / 255.0f;
        return img;
    }

private:
    GLuint tex_ = 0, fbo_ = 0;
    glm::ivec2 size_{0};
};

// One shown frame is input(), frame(), present(); the loop runs until the window closes, Esc,
// or --exit-after frames.
class ViewLoop {
public:
    ViewLoop(const ViewOptions& o, Window& win, Input& in, Runtime& rt, view::ViewSession& session, const Scene& scene,
             std::vector<view::ScriptEvent> script)
        : o_(o), win_(win), in_(in), rt_(rt), session_(session), script_(std::move(script)), scripted_(!o.script.empty()),
          show_ui_(!o.no_ui), cam_(start_camera(o, scene), scene.bounds(), o.size) {
        clock_.t_min = scene.lines.time_min();
        clock_.t_max = scene.lines.time_max();
        clock_.playing = !o.time;
        clock_.t = o.time ? *o.time : clock_.t_min;
        watch_.watch(session_.watched_files());
        info_.graphs = shipped_graphs();
        info_.backend = rt_.gl->renderer() + " - " + session_.profiler().backend_description();
    }

    bool running() const {
        return !quit_ && !glfwWindowShouldClose(win_.get()) && (o_.exit_after == 0 || shown_ < o_.exit_after);
    }
    void input();
    void frame();
    void present();
    // Writes --screenshot and --screenshot-window; the exit status (1: a scripted change failed).
    int finish();

private:
    static Camera start_camera(const ViewOptions& o, const Scene& scene) {
        const double t = o.time ? *o.time : scene.lines.time_min();
        // render's default framing (the data's projected points fill the frame), so the window
        // shows what `pathlet render` writes
        return o.camera.empty() ? frame_points(scene.bounds(), framing_points(scene), o.size)
                                : CameraPath::load(o.camera).at(t, scene.bounds(), o.size);
    }
    void apply_key(const std::string& k);
    void poll_files();
    void copy_command();
    void update_timing();
    void update_title();

    const ViewOptions& o_;
    Window& win_;
    Input& in_;
    Runtime& rt_;
    view::ViewSession& session_;
    std::vector<view::ScriptEvent> script_;
    const bool scripted_;
    bool show_ui_, screenshot_now_ = false, quit_ = false;
    view::OrbitView cam_;
    view::Playback clock_;
    view::FileWatch watch_;
    view::PanelInfo info_;
    view::PanelActions act_;
    OutputBlit blit_;
    std::string shown_error_;
    Image last_;
    WindowCopy window_copy_;
    long shown_ = 0;
    size_t next_event_ = 0;
    uint64_t index_ = 0;
    std::chrono::steady_clock::time_point wall_ = std::chrono::steady_clock::now(), last_poll_ = wall_, frame_start_;
};

void ViewLoop::input() {
    act_ = {};
    screenshot_now_ = false;
    // Scripted events for this frame go through the same paths as real input.
    for (; next_event_ < script_.size() && script_[next_event_].frame <= shown_; ++next_event_) {
        const view::ScriptEvent& e = script_[next_event_];
        if (!e.key.empty()) in_.keys.push_back(e.key);
        if (e.button == "left") in_.orbit_dx += e.dx, in_.orbit_dy += e.dy;
        else if (!e.button.empty()) in_.pan_dx += e.dx, in_.pan_dy += e.dy;
        in_.scroll += e.scroll;
        if (!e.set.empty()) act_.sets.emplace_back(e.set.substr(0, e.set.find('=')), e.set.substr(e.set.find('=') + 1));
        if (!e.graph.empty()) {
            try {
                act_.switch_to = resolve_graph_path(e.graph);
            } catch (const GraphNotFound&) {  // the session says it cannot switch and keeps the graph shown
                act_.switch_to = e.graph;
            }
        }
        act_.reload |= e.reload;
    }
    for (; !in_.keys.empty(); in_.keys.pop_front()) apply_key(in_.keys.front());
    if (in_.orbit_dx != 0 || in_.orbit_dy != 0) cam_.orbit(in_.orbit_dx, in_.orbit_dy);
    if (in_.pan_dx != 0 || in_.pan_dy != 0) cam_.pan(in_.pan_dx, in_.pan_dy);
    if (in_.scroll != 0) cam_.zoom(in_.scroll);
    in_.orbit_dx = in_.orbit_dy = in_.pan_dx = in_.pan_dy = in_.scroll = 0;
}

void ViewLoop::apply_key(const std::string& k) {
    const double step = in_.shift ? 1.0 : 0.1;
    if (k == "space") clock_.playing = !clock_.playing;
    else if (k == "left") clock_.scrub(-step);
    else if (k == "right") clock_.scrub(step);
    else if (k == "up") clock_.speed *= 2.0;
    else if (k == "down") clock_.speed *= 0.5;
    else if (k == "l") clock_.loop = !clock_.loop;
    else if (k == "r") cam_.reset();
    else if (k == "s") screenshot_now_ = true;
    else if (k == "tab") show_ui_ = !show_ui_;
    else if (k == "?") std::fprintf(stdout, "%s", kHelp);
}

void ViewLoop::frame() {
    // The panels of the previous frame asked for these; they apply before this frame runs.
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_ui_) view::draw_panels(session_, clock_, info_, act_);
    poll_files();
    for (const auto& [name, value] : act_.sets) session_.set(name, value);
    if (!act_.switch_to.empty()) session_.switch_graph(act_.switch_to);
    if (act_.reload) session_.rebuild();
    if (!act_.sets.empty() || !act_.switch_to.empty() || act_.reload) watch_.watch(session_.watched_files());
    if (act_.reset_view) cam_.reset();
    if (session_.error() != shown_error_) {
        shown_error_ = session_.error();
        if (!shown_error_.empty()) std::fprintf(stderr, "view: error (still showing the last good graph):\n%s\n", shown_error_.c_str());
        else std::fprintf(stderr, "view: the graph works again\n");
    }
    if (act_.copy_command) copy_command();
    frame_start_ = std::chrono::steady_clock::now();
    session_.executor().run_frame({index_++, clock_.t, cam_.camera()});
}

// Hot reload: the graph and shader files, polled twice a second (every 12 frames when scripted).
void ViewLoop::poll_files() {
    const auto now = std::chrono::steady_clock::now();
    if (!(scripted_ ? shown_ % 12 == 0 : now - last_poll_ > std::chrono::milliseconds(500))) return;
    last_poll_ = now;
    const auto changed = watch_.changed();
    if (changed.empty()) return;
    std::fprintf(stderr, "view: %s changed, reloading\n", changed.front().c_str());
    act_.reload = true;
}

void ViewLoop::copy_command() {
    const std::string camera_file = (std::filesystem::path(o_.screenshot_dir) / "pathlet_view_camera.json").string();
    write_camera(camera_file, cam_.camera());
    info_.command = render_command(session_, clock_.t, o_.size, camera_file);
    glfwSetClipboardString(win_.get(), info_.command.c_str());
    std::fprintf(stdout, "%s\n", info_.command.c_str());
}

void ViewLoop::present() {
    const Texture tex = session_.executor().texture(session_.compiled().outputs.front().resource);
    blit_.draw(tex, o_.size);
    if (screenshot_now_) last_ = read_texture(tex.id, tex.width, tex.height, 0, 4);
    info_.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start_).count();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    // The window's pixels are gone after the swap: kept on the GPU on every frame (closing the
    // window comes unannounced), read once in finish().
    if (!o_.screenshot_window.empty()) window_copy_.copy(o_.size);
    if (screenshot_now_) {
        char name[64];
        std::snprintf(name, sizeof name, "pathlet_view_%05ld.png", shown_);
        const std::string path = (std::filesystem::path(o_.screenshot_dir) / name).string();
        write_image(path, last_);
        std::fprintf(stderr, "screenshot: %s\n", path.c_str());
    }
    update_timing();
    update_title();
    glfwSwapBuffers(win_.get());
    glfwPollEvents();
    quit_ = glfwGetKey(win_.get(), GLFW_KEY_ESCAPE) == GLFW_PRESS && !ui_wants_keys();
    const auto now = std::chrono::steady_clock::now();
    clock_.advance(scripted_ ? 0.04 : std::chrono::duration<double>(now - wall_).count());
    wall_ = now;
    ++shown_;
}

// Per-pass timing bars: medians of the last 30 frames whose GPU times are in, then those are
// forgotten (bounded memory over an afternoon). Never waits for the GPU: only ready timer
// queries are collected, and frames still in flight carry over to the next 30.
void ViewLoop::update_timing() {
    Profiler& prof = session_.profiler();
    prof.collect_ready();
    if (prof.frames_timed() < 30) return;
    info_.timing.clear();
    for (const auto& p : prof.passes()) info_.timing.push_back({p.name, p.gpu_ms.median});
    info_.backend = rt_.gl->renderer() + " - " + prof.backend_description();
    prof.forget_timed();
}

void ViewLoop::update_title() {
    double window = 0.0;
    for (const auto& v : session_.graph().variables)
        if (v.name == "window" && v.value.is_number()) window = v.value.get<double>();
    char title[256];
    std::snprintf(title, sizeof title, "pathlet view - %s - t = %.2f s (window %.2g s) x%.3g %s%s - %.0f ms",
                  graph_display_name(session_.graph()).c_str(), clock_.t, window, clock_.speed,
                  clock_.playing ? "playing" : "paused", clock_.loop ? ", loop" : "", info_.frame_ms);
    glfwSetWindowTitle(win_.get(), title);
}

int ViewLoop::finish() {
    if (!o_.screenshot.empty()) {
        if (shown_ == 0) throw std::runtime_error("view: no frame was shown; no screenshot written");
        // The last frame's output is still in its texture: one read at the end, not one a frame.
        const Texture tex = session_.executor().texture(session_.compiled().outputs.front().resource);
        write_image(o_.screenshot, read_texture(tex.id, tex.width, tex.height, 0, 4));
        std::fprintf(stderr, "screenshot: %s\n", o_.screenshot.c_str());
    }
    if (!o_.screenshot_window.empty()) {
        if (window_copy_.empty()) throw std::runtime_error("view: no frame was shown; no window screenshot written");
        write_image(o_.screenshot_window, window_copy_.read());
        std::fprintf(stderr, "window screenshot: %s\n", o_.screenshot_window.c_str());
    }
    return scripted_ && !session_.error().empty() ? 1 : 0;  // a script whose last change failed
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
           "loop; with --time it starts paused there (and --camera starts from its camera at that time).\n"
           "Close the window or press Esc to quit.");
    ViewOptions o;
    o.declare(a);
    a.example("pathlet view", "the built-in phantom through variant1_lineao, playing")
        .example("pathlet view isl --time 9 --set window=3", "illuminated streamlines, paused at 9 s, 3 s pathlets")
        .example("xvfb-run -a pathlet view --exit-after 10 --screenshot shot.png", "headless, for tests");
    if (!a.parse(argv)) return 0;
    if (o.exit_after < 0) throw UsageError("--exit-after must be >= 0");
    const std::string graph_path = resolve_graph_path(o.graph);
    std::vector<view::ScriptEvent> script;
    if (!o.script.empty()) script = view::load_script(o.script);

    Window win;
    Input input;
    win.open(o.size, /*vsync=*/o.script.empty(), &input, install_callbacks);
    Runtime rt;
    o.plugins.load(rt);
    o.sets = rt.user_sets(o.sets);
    const Scene scene = o.data.load(false);
    if (o.time) {  // a start outside the data would show nothing (issue 41): the span, before a frame
        char given[32];
        std::snprintf(given, sizeof given, "%g", *o.time);
        check_time_in_data(TimeRange{*o.time, *o.time}, given, scene, o.allow_empty);
    }
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());
    win.open_ui();
    // The graph: compiled and set up once (as render does); changed in place afterwards.
    GpuScene gpu;
    gpu.upload(scene);
    view::ViewSession session(rt, gpu, o.size, graph_path, o.sets);
    ViewLoop loop(o, win, input, rt, session, scene, std::move(script));
    std::fprintf(stderr, "%s", kHelp);
    while (loop.running()) {
        loop.input();
        loop.frame();
        loop.present();
    }
    return loop.finish();
}

PATHLET_COMMAND("view", "show a graph's output live in a window: camera, clock, parameter panels, hot reload", run);

}  // namespace
}  // namespace pathlet::cli
