// `pathlet view`: the command's options, then the viewer (engine/apps/view/viewer.hpp: the
// window, its loop and input) on the graph, plugins and data they name.
#include "commands.hpp"
#include "common_options.hpp"
#include "renderer.hpp"
#include "view/viewer.hpp"

#include <cstdio>
#include <optional>

namespace pathlet::cli {
namespace {

struct ViewOptions {
    std::string graph = "variant1_lineao";
    view::ViewSettings view;
    std::vector<std::string> sets;
    bool allow_empty = false;
    PluginOptions plugins;
    SceneOptions data;

    void declare(Args& a) {
        a.positional("GRAPH", graph, "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
            .option("time", view.time, "T", "start paused at this animation time in seconds (default: play from the start)")
            .flag("allow-empty-frames", allow_empty,
                  "start at the --time asked for even where it lies outside the data's time span (an empty frame); "
                  "without it such a time is an error naming the span");
        declare_size(a, view.size, "window and output size in pixels");
        declare_sets(a, sets);
        declare_camera(a, view.camera);
        a.option("exit-after", view.exit_after, "N", "quit after N shown frames (0: run until closed)")
            .option("screenshot", view.screenshot, "FILE", "on exit, write the graph output of the last frame (PNG/EXR)")
            .option("screenshot-window", view.screenshot_window, "FILE", "on exit, write the whole window (graph output and panels) as PNG")
            .option("screenshot-dir", view.screenshot_dir, "DIR",
                    "where the s key writes pathlet_view_<frame>.png (and 'copy as --set' its camera)")
            .option("script", view.script, "FILE", "scripted input (JSON events per frame, fixed 1/25 s clock; see view/view_script.hpp)")
            .flag("no-ui", view.no_ui, "no panels (tab shows them)");
        plugins.declare(a);
        data.declare(a);
    }
};

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
    if (o.view.exit_after < 0) throw UsageError("--exit-after must be >= 0");
    const std::string graph_path = resolve_graph_path(o.graph);
    view::Viewer viewer(o.view);  // the window first: no display fails before anything loads
    Runtime rt;
    o.plugins.load(rt);
    o.sets = rt.user_sets(o.sets);
    const Scene scene = o.data.load(false);
    if (o.view.time) {  // a start outside the data would show nothing: the span, before a frame
        char given[32];
        std::snprintf(given, sizeof given, "%g", *o.view.time);
        check_time_in_data(TimeRange{*o.view.time, *o.view.time}, given, scene, o.allow_empty);
    }
    return viewer.run(rt, scene, graph_path, o.sets);
}

PATHLET_COMMAND("view", "show a graph's output live in a window: camera, clock, parameter panels, hot reload", run);

}  // namespace
}  // namespace pathlet::cli
