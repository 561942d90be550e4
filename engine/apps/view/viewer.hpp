// `pathlet view` without its command line: a window (OpenGL 4.5 core through GLFW) that shows a
// graph's first output live, on the same engine, plugins and scene loading as `render`. The
// engine adopts the window's context (GlContext::adopt_current), so passes run unchanged.
//   viewer        this, and its loop: one shown frame is input, frame (panels, hot reload,
//                 the graph), present
//   view_window   the window and Dear ImGui
//   view_input    keys, drags and the wheel, as the window delivers them
//   window_pixels the output drawn on the window, the window kept for --screenshot-window
//   view_session  the graph: parameter changes, graph switches, hot reload
//   view_panels, orbit_view, file_watch, view_script: the panels, camera and clock, file
//                 polling, scripted input
#pragma once

#include "runtime.hpp"
#include "view/view_input.hpp"
#include "view/view_script.hpp"
#include "view/view_window.hpp"

#include <pathlet/scene.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pathlet::view {

// How the viewer shows a graph: the window, the start, the screenshots, scripted input.
struct ViewSettings {
    glm::ivec2 size{1280, 720};       // window and output size in pixels
    std::optional<double> time;       // start paused here; none: play the data's span from its start
    std::string camera;               // a camera path file; "": render's default framing
    std::string screenshot;           // on exit, the graph output of the last frame
    std::string screenshot_window;    // on exit, the whole window (output and panels)
    std::string screenshot_dir = "."; // where the s key and 'copy as --set' write
    std::string script;               // scripted input (view_script.hpp); a fixed 1/25 s clock
    long exit_after = 0;              // quit after this many shown frames (0: when closed)
    bool no_ui = false;               // start without panels (tab shows them)
};

class Viewer {
public:
    // Reads the script and opens the window: a missing display or a bad script fails here,
    // before anything is loaded. Vsync unless scripted.
    explicit Viewer(const ViewSettings& settings);
    // Shows `graph_path` (with the --set overrides `sets`) on `scene` until the window closes,
    // Esc or exit_after; then writes the screenshots. Adopts the window's GL context into rt.
    // Returns the exit status: 1 when a scripted change left the graph in error.
    int run(Runtime& rt, const Scene& scene, const std::string& graph_path, const std::vector<std::string>& sets);

private:
    const ViewSettings settings_;
    std::vector<ScriptEvent> script_;
    Input input_;
    Window window_;
};

}  // namespace pathlet::view
