#include "common_options.hpp"

#include "io/units.hpp"
#include "renderer.hpp"

#include <algorithm>
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
        .option("time-step", time_step, "SECONDS", "plain-text rows: seconds between samples (0: 0.01 s)")
        .option("units", units, "LENGTH[,VELOCITY]",
                "units of the data where the file does not say them, e.g. mm or m,m/s (velocity default: LENGTH/s "
                "when time is in seconds); shown by the legend")
        .flag("streamlines", streamlines,
              "VTK lines with neither time nor velocity (streamlines, centrelines) load as lines drawn whole")
        .flag("pseudo-time", pseudo_time, "lines without time (tracts, --streamlines) animate along a pseudo-time (arc length)");
}

io::LoadOptions ArrayOptions::load_options() const {
    if (time_step < 0) throw UsageError("--time-step must be >= 0");
    try {
        Units probe;
        io::apply_units_option(probe, units);  // a bad spec is a usage error before any loading
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    io::LoadOptions o;
    o.time_array = time_array;
    o.velocity_array = velocity_array;
    o.time_step = time_step;
    o.units = units;
    o.streamlines = streamlines;
    o.pseudo_time = pseudo_time;
    return o;
}

void SceneOptions::declare(Args& a) {
    a.list("data", data, "FILE",
           "pathlines: .vtk (legacy), .vtp, .pathlet, text rows 'x y z x y z ...', or tracts .trk/.tck; several files, "
           "a folder (its data files) or a glob are joined, each file a bundle named after it (colormap=bundle); "
           "takes every argument up to the next option")
        .option("mesh", mesh, "FILE", "vessel wall: .gltf/.glb, .stl or .obj (optional)")
        .option("phantom", phantom, "study|small[:density=N]",
                "built-in aortic-arch phantom used when --data is not given; ':density=N' makes it N times\n"
                "denser (N x the lines: more seeds, the same vessel and time; deterministic, cached)");
    arrays.declare(a);
}

SceneSource SceneOptions::source() const {
    SceneSource s;
    s.data = data;
    s.mesh = mesh;
    s.phantom = phantom.value;
    s.load = arrays.load_options();
    return s;
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
    a.option("timing", timing, "auto|gpu|finish|cpu",
             "pass timing: GL timestamp queries (gpu), glFinish-bracketed CPU clock (finish) or process CPU time "
             "(cpu: llvmpipe's work, steady on a busy machine; no measure of a GPU); auto: finish on llvmpipe, "
             "timestamps on a GPU");
}

void check_time_in_data(const TimeRange& t, const std::string& given, const Scene& scene, bool allow_empty) {
    if (allow_empty || scene.lines.timeless) return;
    const double t0 = scene.lines.time_min(), t1 = scene.lines.time_max();
    const double slack = 1e-6 * std::max(1.0, t1 - t0);
    const std::vector<double> times = t.times();
    const double first = times.front(), last = times.back();
    if (first >= t0 - slack && last <= t1 + slack) return;
    char span[160];
    std::snprintf(span, sizeof span, "%g..%g s", t0, t1);
    const std::string what = times.size() == 1 ? "is outside" : "reaches outside";
    throw InputError("--time " + given + " " + what + " the data's time span, " + span + " (" + scene.source +
                     "): its frames would be empty; give a time within " + span +
                     ", or --allow-empty-frames to render them anyway");
}

}  // namespace pathlet::cli
