#include "run_experiment.hpp"

#include "calibration.hpp"
#include "results.hpp"

#include "common/scene_source.hpp"

#include "gl_context.hpp"
#include "renderer.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

namespace pathlet::cli::bench {

namespace fs = std::filesystem;
using nlohmann::json;

Scene load_data_set(const DataSet& ds) {
    SceneSource src;
    src.phantom = ds.phantom;
    src.data = ds.file;
    src.mesh = ds.mesh;
    return load_scene(src, true);
}

json graph_info(const Experiment& e, const std::string& origin) {
    json info = json::object();
    for (size_t gi = 0; gi < e.graphs.size(); ++gi) {
        std::string path;
        try {
            path = resolve_graph_path(e.graphs[gi].graph);
        } catch (const GraphNotFound& ex) {
            if (origin.empty()) throw;  // a command line's graph list: the user's typo, exit 2
            throw std::runtime_error(origin + ": /graphs/" + std::to_string(gi) + ": " + ex.what());
        }
        if (!fs::is_regular_file(path))
            throw std::runtime_error((origin.empty() ? "" : origin + ": /graphs/" + std::to_string(gi) + ": ") +
                                     "no graph file or shipped graph named '" + e.graphs[gi].graph + "'");
        info[e.graphs[gi].label] = graph_entry(e.graphs[gi].graph, path);
    }
    return info;
}

namespace {
constexpr int kCalibrationSamples = 3;  // on each side of a run

// The --set list of one run: the experiment's, its graph's, the sweep's value.
std::vector<std::string> run_sets(const Experiment& e, const Run& run) {
    std::vector<std::string> sets = e.sets;
    const auto& g = e.graphs[run.graph];
    sets.insert(sets.end(), g.sets.begin(), g.sets.end());
    if (!e.sweep.param.empty()) sets.push_back(e.sweep.param + "=" + run.sweep_value);
    return sets;
}
}  // namespace

json run_experiment(Runtime& rt, const Experiment& e, const ExperimentSettings& s, const ExperimentHooks& hooks) {
    RenderOptions base;
    if (!e.time.empty()) base.time = parse_time_range(e.time);
    base.timing = s.timing;
    base.repeat = e.frames;
    base.warmup = e.warmup;
    base.camera_path = e.camera;
    base.orbit_deg_per_s = e.orbit_deg_per_s;
    base.write_images = false;
    base.quiet = true;

    const std::vector<Run> runs = plan_runs(e);
    size_t mine = 0;
    for (size_t k = 0; k < runs.size(); ++k) mine += s.shard.owns(k);
    // Every graph with the sets of its runs before any work (GraphError): a wrong name or value
    // for the last graph or sweep value must not wait for the runs before it.
    std::set<std::pair<size_t, std::string>> checked;
    for (size_t k = 0; k < runs.size(); ++k)
        if (s.shard.owns(k) && checked.emplace(runs[k].graph, runs[k].sweep_value).second)
            rt.load_graph(resolve_graph_path(e.graphs[runs[k].graph].graph), run_sets(e, runs[k]));
    rt.ensure_gl(true);
    // A GPU's clock settles only under seconds of load: warm up by time there (llvmpipe has no
    // governor, and a second of its frames would only slow the runs down).
    if (!is_software_renderer(rt.gl->renderer())) base.warmup_seconds = 1.0;

    Calibration calibration;  // the machine's speed, timed before and after every run
    Results results(e, s.command, rt.gl->renderer(), s.graphs, runs.size(), s.shard);
    results.set_complete(mine == 0);
    if (hooks.on_report) hooks.on_report(results.doc(), nullptr);  // a shard with no runs still leaves its results

    std::optional<Scene> scene;
    size_t scene_of = size_t(-1), done = 0;
    for (size_t k = 0; k < runs.size(); ++k) {
        if (!s.shard.owns(k)) continue;
        if (hooks.stop && hooks.stop()) break;
        const Run& run = runs[k];
        if (scene_of != run.data) {
            scene.reset();
            scene = hooks.load_data(run.data);
            scene_of = run.data;
            if (e.time.empty()) {  // a time inside this data's span, said
                base.time = default_bench_time(*scene);
                std::fprintf(stderr, "note: %s\n", picked_time_note(base.time, *scene, "the middle").c_str());
            }
            results.add_data(*scene, base.time);
            for (double t : base.time.times())  // an empty picture times nothing worth knowing
                if (t < scene->lines.time_min() || t > scene->lines.time_max()) {
                    std::fprintf(stderr, "warning: time %g s is outside %s's %g..%g s: few or no lines are drawn\n", t,
                                 scene->source.c_str(), scene->lines.time_min(), scene->lines.time_max());
                    break;
                }
        }
        const auto& g = e.graphs[run.graph];
        RenderOptions opt = base;
        opt.graph_path = resolve_graph_path(g.graph);
        opt.sets = run_sets(e, run);
        opt.size = parse_size(run.size);
        const std::vector<double> calibrated_before = calibration.samples_ms(kCalibrationSamples);
        RenderResult r = render(rt, *scene, opt);
        const std::vector<double> calibrated_after = calibration.samples_ms(kCalibrationSamples);
        std::string image;
        if (!s.image_dir.empty()) {  // what the time bought: one frame, at the first time, written
            RenderOptions io = opt;
            io.time = TimeRange{base.time.times().front(), base.time.times().front()};
            io.repeat = 1;
            io.warmup = 0;
            io.write_images = true;
            io.out_dir = s.image_dir + "/images/run" + std::to_string(k);
            RenderResult ir = render(rt, *scene, io);
            for (const auto& f : ir.files)
                if (image.empty() && fs::path(f).extension() == ".png") image = fs::relative(f, s.image_dir).generic_string();
        }
        results.add_run(k, run, g, opt.graph_path, opt.sets, scene->source, r.profiler, image);
        results.add_calibration(Calibration::description(), calibrated_before, calibrated_after);
        results.set_complete(++done == mine);
        const RunDone finished{run, r.profiler, *scene, done, mine, r.incomplete_frames, r.frames};
        if (hooks.on_report) hooks.on_report(results.doc(), &finished);
    }
    return results.doc();
}

}  // namespace pathlet::cli::bench
