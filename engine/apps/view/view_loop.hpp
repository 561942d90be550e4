// One shown frame of the viewer is input(), frame(), present(): input from the window and the
// script into the clock, camera and actions; the panels, hot reload and the actions, then the
// graph; the output and panels on the window, and screenshots. The loop runs until the window
// closes, Esc, or exit_after frames.
#pragma once

#include "image_io.hpp"
#include "runtime.hpp"
#include "view/orbit_view.hpp"
#include "view/file_watch.hpp"
#include "view/view_input.hpp"
#include "view/view_panels.hpp"
#include "view/view_script.hpp"
#include "view/view_session.hpp"
#include "view/view_window.hpp"
#include "view/viewer.hpp"
#include "view/window_pixels.hpp"

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace pathlet::view {

// The keys and what they do: printed when the viewer starts and on '?'.
extern const char* const kKeysHelp;

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

}  // namespace pathlet::view
