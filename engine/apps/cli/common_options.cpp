#include "common_options.hpp"

#include "fraction_progress.hpp"
#include "io/mesh_io.hpp"
#include "phantom/phantom.hpp"
#include "util/text.hpp"

#include <cstdio>

namespace pathlet::cli {

void PluginOptions::declare(Args& a, bool graph_files) {
    a.multi("plugin-dir", dirs, "DIR",
            "also load plugins from DIR (searched before PATHLET_PLUGIN_PATH and the built-in folder)");
    if (graph_files)
        a.flag("trust-graph-plugins", trust_graph_plugins,
               "load the plugin folders the graph files name (\"plugin_dirs\") for this run even when they are not "
               "trusted (see 'pathlet trust --help'); loading a plugin runs its code");
}

void PluginOptions::load(Runtime& rt) const {
    rt.trust_graph_plugins = trust_graph_plugins;
    rt.load_plugins(dirs);
}

void ArrayOptions::declare(Args& a) {
    a.option("time-array", time_array, "NAME", "point array holding time (default: time, Time, t, IntegrationTime)")
        .option("velocity-array", velocity_array, "NAME", "point array holding velocity (default: velocity, Velocity, U, v)")
        .option("time-step", time_step, "SECONDS", "plain-text rows: seconds between samples (0: 0.01 s)");
}

io::LoadOptions ArrayOptions::load_options() const {
    if (time_step < 0) throw UsageError("--time-step must be >= 0");
    io::LoadOptions o;
    o.time_array = time_array;
    o.velocity_array = velocity_array;
    o.time_step = time_step;
    return o;
}

void SceneOptions::declare(Args& a) {
    a.option("data", data, "FILE", "pathlines: .vtk (legacy), .vtp, .pathlet, or text rows 'x y z x y z ...'")
        .option("mesh", mesh, "FILE", "vessel wall: .gltf/.glb, .stl or .obj (optional)")
        .option("phantom", phantom, "study|small", "built-in aortic-arch phantom used when --data is not given");
    arrays.declare(a);
}

Scene SceneOptions::load(bool quiet) const {
    Scene scene;
    if (data.empty()) {
        // Generated once (tracing takes a while on two cores), then read from the cache.
        FractionProgress bar("phantom '" + phantom.value + "'", quiet);
        scene = phantom::load_or_make_phantom(phantom.value, bar.callback());
        bar.finish(std::to_string(scene.lines.line_count()) + " lines");
    } else {
        io::LoadReport rep;
        scene.lines = io::load_pathlines(data, arrays.load_options(), &rep);
        scene.source = data;
        // Nothing to draw is an error, not a blank picture (pathlet info still shows the numbers).
        if (scene.lines.line_count() == 0) {
            std::vector<std::string> dropped;
            for (const auto& w : rep.warnings)
                if (w.rfind("dropped", 0) == 0) dropped.push_back(w);
            throw DataError(data + ": no line to draw after repair (" +
                            (dropped.empty() ? std::string("the file holds no lines") : text::join(dropped, "; ")) +
                            "); 'pathlet info " + text::shell_quote(data) + "' shows what it holds");
        }
        for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s: %s\n", data.c_str(), w.c_str());
    }
    if (!mesh.empty()) {
        io::LoadReport rep;
        scene.mesh = io::load_mesh(mesh, &rep);
        for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s: %s\n", mesh.c_str(), w.c_str());
    }
    if (!quiet)
        std::fprintf(stderr, "data: %s — %zu lines, %zu points, t %.2f..%.2f s, speed %.3g..%.3g%s\n", scene.source.c_str(),
                     scene.lines.line_count(), scene.lines.point_count(), scene.lines.time_min(),
                     scene.lines.time_max(), scene.lines.speed_min(), scene.lines.speed_max(),
                     scene.mesh ? (", wall " + std::to_string(scene.mesh->index.size() / 3) + " triangles").c_str() : "");
    return scene;
}

void declare_sets(Args& a, std::vector<std::string>& sets) {
    a.multi("set", sets, "NAME=VALUE", "override a graph variable or a pass parameter: --set window=3, --set lineao.strength=2");
}

void declare_size(Args& a, glm::ivec2& size, const std::string& what) { a.option("size", size, "WxH", what); }

void declare_camera(Args& a, std::string& file) {
    a.option("camera", file, "FILE",
             "camera path JSON: {\"keyframes\": [{\"time\", \"eye\", \"target\", \"up\", \"fov\"}]} (default: frame the data)");
}

void declare_timing(Args& a, TimingBackend& timing) {
    a.option("timing", timing, "auto|gpu|finish",
             "pass timing: GL timestamp queries (gpu) or glFinish-bracketed CPU clock (finish); auto: finish on "
             "llvmpipe, timestamps on a GPU");
}

}  // namespace pathlet::cli
