#include "view/viewer.hpp"

#include "camera.hpp"
#include "gl_context.hpp"
#include "image_io.hpp"
#include "plugin_host.hpp"
#include "renderer.hpp"
#include "util/atomic_file.hpp"
#include "util/text.hpp"
#include "view/file_watch.hpp"
#include "view/orbit_view.hpp"
#include "view/view_panels.hpp"
#include "view/view_session.hpp"
#include "view/window_pixels.hpp"

#include <pathlet/gpu_scene.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>

namespace pathlet::view {
namespace {

// The keys and what they do: printed when the viewer starts and on '?'.
const char* const kKeysHelp =
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
std::string render_command(const ViewSession& session, double t, glm::ivec2 size, const std::string& camera_file) {
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

// One shown frame is input(), frame(), present(): input from the window and the script into the
// clock, camera and actions; the panels, hot reload and the actions, then the graph; the output
// and panels on the window, and screenshots. The loop runs until the window closes, Esc, or
// exit_after frames.
class ViewLoop {
public:
    ViewLoop(const ViewSettings& s, Window& win, Input& in, Runtime& rt, ViewSession& session, const Scene& scene,
             std::vector<ScriptEvent> script);

    bool running() const;
    void input();
    void frame();
    void present();
    // Writes --screenshot and --screenshot-window; the exit status (1: a scripted change failed).
    int finish();

private:
    static Camera start_camera(const ViewSettings& s, const Scene& scene);
    void take_script_events();
    void apply_key(const std::string& k);
    void poll_files();
    void copy_command();
    void write_screenshot();
    void update_timing();
    void update_title();

    const ViewSettings& s_;
    Window& win_;
    Input& in_;
    Runtime& rt_;
    ViewSession& session_;
    std::vector<ScriptEvent> script_;
    const bool scripted_;
    bool show_ui_, screenshot_now_ = false, quit_ = false;
    OrbitView cam_;
    Playback clock_;
    FileWatch watch_;
    PanelInfo info_;
    PanelActions act_;
    OutputBlit blit_;
    std::string shown_error_;
    Image last_;
    WindowCopy window_copy_;
    long shown_ = 0;
    size_t next_event_ = 0;
    uint64_t index_ = 0;
    std::chrono::steady_clock::time_point wall_ = std::chrono::steady_clock::now(), last_poll_ = wall_, frame_start_;
};

}  // namespace

ViewLoop::ViewLoop(const ViewSettings& s, Window& win, Input& in, Runtime& rt, ViewSession& session, const Scene& scene,
                   std::vector<ScriptEvent> script)
    : s_(s), win_(win), in_(in), rt_(rt), session_(session), script_(std::move(script)), scripted_(!s.script.empty()),
      show_ui_(!s.no_ui), cam_(start_camera(s, scene), scene.bounds(), s.size) {
    clock_.t_min = scene.lines.time_min();
    clock_.t_max = scene.lines.time_max();
    clock_.playing = !s.time;
    clock_.t = s.time ? *s.time : clock_.t_min;
    watch_.watch(session_.watched_files());
    info_.graphs = shipped_graphs();
    info_.backend = rt_.gl->renderer() + " - " + session_.profiler().backend_description();
}

Camera ViewLoop::start_camera(const ViewSettings& s, const Scene& scene) {
    const double t = s.time ? *s.time : scene.lines.time_min();
    // render's default framing (the data's projected points fill the frame), so the window
    // shows what `pathlet render` writes
    return s.camera.empty() ? frame_points(scene.bounds(), framing_points(scene), s.size)
                            : CameraPath::load(s.camera).at(t, scene.bounds(), s.size);
}

bool ViewLoop::running() const {
    return !quit_ && !glfwWindowShouldClose(win_.get()) && (s_.exit_after == 0 || shown_ < s_.exit_after);
}

void ViewLoop::input() {
    act_ = {};
    screenshot_now_ = false;
    take_script_events();
    for (; !in_.keys.empty(); in_.keys.pop_front()) apply_key(in_.keys.front());
    if (in_.orbit_dx != 0 || in_.orbit_dy != 0) cam_.orbit(in_.orbit_dx, in_.orbit_dy);
    if (in_.pan_dx != 0 || in_.pan_dy != 0) cam_.pan(in_.pan_dx, in_.pan_dy);
    if (in_.scroll != 0) cam_.zoom(in_.scroll);
    in_.orbit_dx = in_.orbit_dy = in_.pan_dx = in_.pan_dy = in_.scroll = 0;
}

// Scripted events for this frame go through the same paths as real input.
void ViewLoop::take_script_events() {
    for (; next_event_ < script_.size() && script_[next_event_].frame <= shown_; ++next_event_) {
        const ScriptEvent& e = script_[next_event_];
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
    else if (k == "?") std::fprintf(stdout, "%s", kKeysHelp);
}

void ViewLoop::frame() {
    // The panels of the previous frame asked for these; they apply before this frame runs.
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_ui_) draw_panels(session_, clock_, info_, act_);
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
    const std::string camera_file = (std::filesystem::path(s_.screenshot_dir) / "pathlet_view_camera.json").string();
    write_camera(camera_file, cam_.camera());
    info_.command = render_command(session_, clock_.t, s_.size, camera_file);
    glfwSetClipboardString(win_.get(), info_.command.c_str());
    std::fprintf(stdout, "%s\n", info_.command.c_str());
}

void ViewLoop::present() {
    const Texture tex = session_.executor().texture(session_.compiled().outputs.front().resource);
    blit_.draw(tex, s_.size);
    if (screenshot_now_) last_ = read_texture(tex.id, tex.width, tex.height, 0, 4);
    info_.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start_).count();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    // The window's pixels are gone after the swap: kept on the GPU on every frame (closing the
    // window comes unannounced), read once in finish().
    if (!s_.screenshot_window.empty()) window_copy_.copy(s_.size);
    if (screenshot_now_) write_screenshot();
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

// The s key: the graph output of this frame as pathlet_view_<frame>.png in --screenshot-dir.
void ViewLoop::write_screenshot() {
    char name[64];
    std::snprintf(name, sizeof name, "pathlet_view_%05ld.png", shown_);
    const std::string path = (std::filesystem::path(s_.screenshot_dir) / name).string();
    write_image(path, last_);
    std::fprintf(stderr, "screenshot: %s\n", path.c_str());
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
    if (!s_.screenshot.empty()) {
        if (shown_ == 0) throw std::runtime_error("view: no frame was shown; no screenshot written");
        // The last frame's output is still in its texture: one read at the end, not one a frame.
        const Texture tex = session_.executor().texture(session_.compiled().outputs.front().resource);
        write_image(s_.screenshot, read_texture(tex.id, tex.width, tex.height, 0, 4));
        std::fprintf(stderr, "screenshot: %s\n", s_.screenshot.c_str());
    }
    if (!s_.screenshot_window.empty()) {
        if (window_copy_.empty()) throw std::runtime_error("view: no frame was shown; no window screenshot written");
        write_image(s_.screenshot_window, window_copy_.read());
        std::fprintf(stderr, "window screenshot: %s\n", s_.screenshot_window.c_str());
    }
    return scripted_ && !session_.error().empty() ? 1 : 0;  // a script whose last change failed
}

Viewer::Viewer(const ViewSettings& settings) : settings_(settings) {
    if (!settings_.script.empty()) script_ = load_script(settings_.script);
    window_.open(settings_.size, /*vsync=*/settings_.script.empty(), &input_, install_input_callbacks);
}

int Viewer::run(Runtime& rt, const Scene& scene, const std::string& graph_path, const std::vector<std::string>& sets) {
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());
    window_.open_ui();
    // The graph: compiled and set up once (as render does); changed in place afterwards.
    GpuScene gpu;
    gpu.upload(scene);
    ViewSession session(rt, gpu, settings_.size, graph_path, sets);
    ViewLoop loop(settings_, window_, input_, rt, session, scene, std::move(script_));
    std::fprintf(stderr, "%s", kKeysHelp);
    while (loop.running()) {
        loop.input();
        loop.frame();
        loop.present();
    }
    return loop.finish();
}

}  // namespace pathlet::view
