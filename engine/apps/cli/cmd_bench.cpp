// pathlet bench GRAPH... | --experiment FILE | --merge DIR... | --compare BASE [--against CUR]:
// the same data, camera, times and sizes through several graphs; per-pass tables, report files,
// plots, shards for clusters and a noise-aware regression check against a baseline.
// A bench is three steps: plan (the experiment, from a file or the command line, checked before
// any work), run (every run of this shard, results written after each) and report (the summary
// table, the files, the comparison with a baseline). results.json's layout: bench/results.hpp.
#include "bench/compare.hpp"
#include "bench/experiment.hpp"
#include "bench/plots.hpp"
#include "bench/report.hpp"
#include "bench/results.hpp"
#include "bench/run_experiment.hpp"
#include "bench/shard.hpp"
#include "commands.hpp"
#include "common_options.hpp"
#include "graph_errors.hpp"
#include "common/progress.hpp"
#include "renderer.hpp"
#include "util/atomic_file.hpp"
#include "util/output_check.hpp"
#include "util/text.hpp"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

namespace pathlet::cli {
namespace {

namespace fs = std::filesystem;
using bench::Experiment;

volatile std::sig_atomic_t g_interrupted = 0;
void on_sigint(int) { g_interrupted = 1; }

struct BenchOptions {
    std::string graphs, experiment, out, compare, against, report, camera;
    std::optional<Shard> shard;
    std::vector<std::string> merge, sets;
    double threshold = 0.5;
    Given<std::string> sizes{"1280x720"}, time{""};
    Given<int> frames{10}, warmup{3};
    TimingBackend timing = TimingBackend::Auto;
    bool no_images = false, plots = false, quiet = false, allow_empty = false;
    PluginOptions plugins;
    SceneOptions data;

    void declare(Args& a) {
        a.positional("GRAPHS", graphs, "comma-separated graph files or shipped graph names (e.g. variant1_lineao,isl)", false)
            .option("experiment", experiment, "FILE", "run an experiment file (schema: graphs/schema/pathlet-experiment.schema.json)")
            .option("out", out, "DIR",
                    "where the results go: results.json, CSV, SVG, one image per run (GRAPHS: only with --out; "
                    "--experiment: default out/bench/<experiment name>; --merge: required)")
            .option("shard", shard, "I/N", "do part I (0-based) of N of the runs: run k belongs to shard k % N")
            .multi("merge", merge, "DIR", "join shard results folders (repeat) into --out; no rendering")
            .option("compare", compare, "BASELINE.json", "compare with a baseline results.json; exit 1 on a regression")
            .option("against", against, "RESULTS.json", "with --compare: compare these results instead of running")
            .option("threshold", threshold, "FRACTION",
                    "--compare: relative slow-down that counts (0.5 = 50 %; on this shared 2-core machine plain\n"
                    "re-runs drift by up to ~40 %, so use 0.1 only on a quiet, dedicated node)")
            .option("size", sizes, "WxH[,WxH...]", "output sizes to measure (overrides the experiment's)")
            .option("time", time, "T|A:B:STEP",
                    "animation time(s) rendered (overrides the experiment's); default: the middle of the data's time "
                    "span (the study phantom's 9 s)")
            .option("frames", frames, "N", "measured frames per time, after warm-up (overrides the experiment's)")
            .option("warmup", warmup, "N", "frames before timing starts (overrides the experiment's)")
            .multi("set", sets, "[GRAPH:]NAME=VALUE",
                   "override a variable or pass parameter: in every graph, or with GRAPH: (a graph as listed or its "
                   "label, or its position 1, 2, ...) in that one only; unknown names are errors");
        declare_timing(a, timing);
        declare_camera(a, camera);
        a.flag("allow-empty-frames", allow_empty,
               "time the --time asked for even where it lies outside the data's time span (empty frames); "
               "without it such a time is an error naming the span")
            .option("report", report, "PREFIX", "write PREFIX.csv and PREFIX.json with every pass of every run")
            .flag("no-images", no_images, "--experiment or --out: no representative image per run")
            .flag("plots", plots, "--experiment, --merge: also PNG and PDF figures with Matplotlib (python3 -m pathlet.plot)")
            .flag("quiet", quiet, "no progress line");
        plugins.declare(a);
        data.declare(a);
    }
};

// --set for one graph only: "GRAPH:NAME=VALUE" where GRAPH is a graph as listed (its name,
// file or experiment label) or its 1-based position in the list (so one graph can run twice,
// set differently). Plain "NAME=VALUE" goes to every graph. Returns the overrides of graph
// `index` (0-based).
std::vector<std::string> sets_for(const std::vector<std::string>& all, const std::vector<std::string>& graphs, size_t index) {
    std::vector<std::string> out;
    for (const auto& s : all) {
        const size_t colon = s.find(':'), eq = s.find('=');
        if (colon == std::string::npos || (eq != std::string::npos && eq < colon)) {
            out.push_back(s);  // no qualifier (a ':' inside the value does not count)
            continue;
        }
        const std::string q = s.substr(0, colon);
        bool known = false;
        for (size_t i = 0; i < graphs.size(); ++i) {
            bool match = q == graphs[i] || q == std::to_string(i + 1);
            known |= match;
            if (match && i == index) out.push_back(s.substr(colon + 1));
        }
        if (!known) {
            std::string list;
            for (size_t i = 0; i < graphs.size(); ++i) list += (i ? ", " : "") + std::to_string(i + 1) + " = " + graphs[i];
            throw UsageError("--set '" + s + "': '" + q + "' is none of the graphs (" + list + ")");
        }
    }
    return out;
}

// Positional GRAPHS and --set turned into an experiment, so both forms run the same code.
Experiment experiment_from_args(const BenchOptions& o) {
    Experiment e;
    e.name = "bench";
    e.sizes = text::split(o.sizes.value, ',');
    e.time = o.time.value;
    e.frames = o.frames.value;
    e.warmup = o.warmup.value;
    e.camera = o.camera;
    const std::vector<std::string> graphs = text::split(o.graphs, ',');
    for (size_t gi = 0; gi < graphs.size(); ++gi) sets_for(o.sets, graphs, gi);  // bad qualifiers: before any work
    std::set<std::string> labels;
    for (size_t gi = 0; gi < graphs.size(); ++gi) {
        bench::ExperimentGraph g{graphs[gi], graphs[gi], sets_for(o.sets, graphs, gi)};
        for (const auto& s : g.sets)  // label with the overrides only this graph gets
            if (std::find(o.sets.begin(), o.sets.end(), s) == o.sets.end()) g.label += " [" + s + "]";
        if (!labels.insert(g.label).second) g.label += " #" + std::to_string(gi + 1);
        e.graphs.push_back(g);
    }
    return e;
}

int compare_and_report(const json& baseline, const json& current, const BenchOptions& o) {
    if (!(o.threshold > 0)) throw UsageError("--threshold must be > 0 (0.5 = 50 % slower)");
    bench::CompareResult c = bench::compare_reports(baseline, current, o.threshold);
    std::printf("compare against %s (regression: >%.0f %% slower as measured and on the machine's own speed, the "
                "per-frame samples' middle halves apart, rank test p < %.2f)\n%s%s",
                o.compare.c_str(), o.threshold * 100, bench::kMaxP, c.machine.c_str(), c.table.c_str());
    for (const auto& m : c.missing) std::printf("  not in the current results: %s\n", m.c_str());
    std::printf("%d compared, %d regressions, %d faster\n", c.compared, c.regressions, c.improvements);
    if (c.compared == 0) {
        std::fprintf(stderr, "error: nothing in common with the baseline (different graphs or sizes?)\n");
        return 1;
    }
    return c.regressions > 0 ? 1 : 0;
}

// --plots: Matplotlib figures of a results folder; false (reported) when they could not be made.
bool write_plots(const std::string& dir) {
    if (const std::string err = bench::write_matplotlib_plots(dir); !err.empty()) {
        std::fprintf(stderr, "error: --plots: %s\n", err.c_str());
        return false;
    }
    return true;
}

// --merge: shard results joined into the files one unsharded run writes.
int merge(const BenchOptions& o) {
    if (o.out.empty()) throw UsageError("--merge needs --out DIR for the joined results");
    check_output_dir(o.out, "merged results (--out)");
    std::vector<std::pair<std::string, json>> parts;
    for (const auto& dir : o.merge) parts.emplace_back(dir, text::read_json_file(dir + "/results.json", "shard results"));
    const json merged = bench::merge_results(parts, o.out);
    bench::write_report_dir(o.out, merged);
    const size_t planned = merged.value("planned_runs", size_t(0)), joined = merged["runs"].size();
    std::fprintf(stderr, "merged %zu of %zu runs into %s\n", joined, planned, o.out.c_str());
    if (o.plots && !write_plots(o.out)) return 1;
    if (joined != planned) {
        std::fprintf(stderr, "error: %zu runs missing (a shard failed or was not listed)\n", planned - joined);
        return 1;
    }
    return 0;
}

// An experiment file with the command line on top: --set qualified by label, and the sizes,
// time, frames, warm-up, camera and data the command line gives.
Experiment with_command_line(Experiment e, const BenchOptions& o) {
    std::vector<std::string> labels;
    for (const auto& g : e.graphs) labels.push_back(g.label);
    for (size_t gi = 0; gi < e.graphs.size(); ++gi) {
        auto own = sets_for(o.sets, labels, gi);
        e.graphs[gi].sets.insert(e.graphs[gi].sets.end(), own.begin(), own.end());
    }
    if (o.sizes.given) e.sizes = text::split(o.sizes.value, ',');
    if (o.time.given) e.time = o.time.value;
    if (o.frames.given) e.frames = o.frames.value;
    if (o.warmup.given) e.warmup = o.warmup.value;
    if (!o.camera.empty()) e.camera = o.camera;
    if (o.data.given()) e.data.clear();  // a quick run on other data
    return e;
}

// ---- plan -------------------------------------------------------------------------------
// What this bench will do, checked before any work: graphs exist, values parse, outputs are
// writable.
struct Plan {
    Experiment e;
    bench::ExperimentSettings how;  // shard, timing, command, graphs, image folder
    bool from_file = false;
    size_t mine = 0;      // runs of this shard
    std::string out_dir;  // --experiment's folder ("" for a plain bench)
};

Plan make_plan(const BenchOptions& o, const std::vector<std::string>& argv) {
    Plan p;
    p.from_file = !o.experiment.empty();
    if (p.from_file == !o.graphs.empty())
        throw UsageError(p.from_file ? "give either GRAPHS or --experiment, not both" : "missing GRAPHS (or --experiment FILE)");
    if (o.plots && !p.from_file) throw UsageError("--plots needs --experiment (or --merge): figures of a results folder");
    Experiment& e = p.e;
    e = p.from_file ? with_command_line(bench::load_experiment(o.experiment), o) : experiment_from_args(o);
    if (e.frames < 1 || e.warmup < 0) throw UsageError("--frames must be >= 1 and --warmup >= 0");
    try {
        for (const auto& s : e.sizes) parse_size(s);
        if (!e.time.empty()) parse_time_range(e.time);
    } catch (const std::invalid_argument& ex) {
        throw UsageError(ex.what());  // "--size '...'": main() puts "pathlet bench: " before it, once
    }
    if (o.shard) p.how.shard = *o.shard;
    p.how.timing = o.timing;
    std::vector<std::string> command = {"pathlet", "bench"};
    command.insert(command.end(), argv.begin(), argv.end());
    p.how.command = text::shell_command(command);
    p.how.graphs = bench::graph_info(e, p.from_file ? o.experiment : "");
    if (p.from_file || !o.out.empty()) {  // GRAPHS --out DIR writes the same files as an experiment
        const Shard& sh = p.how.shard;
        p.out_dir = !o.out.empty() ? o.out
                                   : "out/bench/" + e.name +
                                         (sh.active() ? "/shard" + std::to_string(sh.index) + "of" + std::to_string(sh.count) : "");
        check_output_dir(p.out_dir, "experiment results (--out)");
        if (!o.no_images) p.how.image_dir = p.out_dir;
    }
    if (!o.report.empty()) check_output_file(o.report + ".csv", "the report (--report)");
    const size_t planned = bench::plan_runs(e).size();
    for (size_t k = 0; k < planned; ++k) p.mine += p.how.shard.owns(k);
    return p;
}

// ---- run --------------------------------------------------------------------------------
// bench::run_experiment runs this shard's runs (the Python module runs them the same way);
// here the files are written after each, so an interrupted or failed bench keeps what it
// finished, and each run's table is printed.
// A run's line chunks per frame, summed over its culling line passes (lines::Drawer's stats):
// drawn in phase 1 (visible last frame) and phase 2, hidden by the depth test, outside the
// frustum. Empty when no pass culls.
struct ChunkCounts {
    double phase1 = 0, phase2 = 0, occluded = 0, frustum = 0;
    bool any = false;
};
ChunkCounts chunk_counts(const Profiler& p) {
    ChunkCounts c;
    for (const auto& pass : p.passes()) {
        auto get = [&](const char* name) {
            auto it = pass.stats.find(name);
            return it == pass.stats.end() ? 0.0 : it->second;
        };
        if (!pass.stats.count("chunks_phase1")) continue;
        c.any = true;
        c.phase1 += get("chunks_phase1");
        c.phase2 += get("chunks_phase2");
        c.occluded += get("chunks_occluded");
        c.frustum += get("chunks_frustum_culled");
    }
    return c;
}

struct Finished {
    json results;
    std::vector<bench::SummaryRow> summary;
    std::string source;
    size_t done = 0;
    // Frames a pass could not draw whole: per run with any, "3, 4, 11"; and the frames of all runs.
    std::vector<std::pair<size_t, std::string>> incomplete;
    size_t incomplete_count = 0, frames = 0;
};

Finished run_plan(const BenchOptions& o, const Plan& p, Runtime& rt) {
    Finished f;
    auto write_files = [&] {
        if (!p.out_dir.empty()) bench::write_report_dir(p.out_dir, f.results);
        if (!o.report.empty()) {
            write_file_atomic(o.report + ".csv", bench::summary_csv(f.results));
            write_file_atomic(o.report + ".json", f.results.dump(1));
        }
    };
    Progress progress("runs", p.mine, o.quiet);
    bench::ExperimentHooks hooks;
    hooks.load_data = [&](size_t d) {
        Scene scene = p.e.data.empty() ? o.data.load(true) : bench::load_data_set(p.e.data[d]);
        // A --time outside the data would time empty frames: the span, before any run.
        if (!o.time.value.empty()) check_time_in_data(parse_time_range(o.time.value), o.time.value, scene, o.allow_empty);
        return scene;
    };
    hooks.stop = [] { return g_interrupted != 0; };
    hooks.on_report = [&](const json& results, const bench::RunDone* run) {
        f.results = results;
        write_files();
        if (!run) return;
        const std::string title = run->run.label + " — " + run->run.size + ", " +
                                  std::to_string(run->scene.lines.line_count()) + " lines";
        if (!o.quiet || !p.from_file) std::printf("%s\n", run->profiler.table(title).c_str());
        std::fflush(stdout);  // whole, before the progress line on stderr (bench 2>&1 | tee)
        bench::SummaryRow row{run->run.label + "  " + run->run.size, run->profiler.frame_ms(), run->profiler.wall_fps()};
        row.gpu_timing = run->profiler.backend() == TimingBackend::GlTimestamp;
        const ChunkCounts c = chunk_counts(run->profiler);
        if (c.any) {
            char chunks[96];
            std::snprintf(chunks, sizeof chunks, "%.0f+%.0f / %.0f / %.0f", c.phase1, c.phase2, c.occluded, c.frustum);
            row.chunks = chunks;
        }
        f.summary.push_back(row);
        f.source = run->scene.source;
        f.done = run->done;
        f.frames += run->frames;
        if (!run->incomplete_frames.empty()) {
            std::string list;
            for (size_t i : run->incomplete_frames) list += (list.empty() ? "" : ", ") + std::to_string(i);
            f.incomplete.emplace_back(run->done - 1, list);
            f.incomplete_count += run->incomplete_frames.size();
        }
        progress.update(f.done, run->run.label);
    };
    bench::run_experiment(rt, p.e, p.how, hooks);
    progress.finish(std::to_string(f.done) + " runs");
    return f;
}

// ---- report -----------------------------------------------------------------------------
int report(const BenchOptions& o, const Plan& p, const Finished& f, const json& baseline) {
    std::printf("summary (%s; %s)\n", f.results.value("gl_renderer", "").c_str(), f.source.c_str());
    for (const json& d : f.results.value("data", json::array()))
        if (d.contains("gpu_points")) std::printf("gpu points (%s): %s\n", d.value("source", "").c_str(), d["gpu_points"].value("summary", "").c_str());
    // Chunks per frame over the culling line passes: drawn in phase 1 + phase 2 / hidden by
    // depth / outside the frustum (the line kit's culling; cull=false: nothing hidden).
    std::fputs(bench::summary_table(f.summary).c_str(), stdout);
    std::fflush(stdout);
    if (!p.out_dir.empty()) std::fprintf(stderr, "wrote %s/results.json, summary.csv, frames.csv and plots\n", p.out_dir.c_str());
    if (o.plots && !write_plots(p.out_dir)) return 1;
    if (!o.report.empty()) std::fprintf(stderr, "wrote %s.csv and %s.json\n", o.report.c_str(), o.report.c_str());
    if (f.incomplete_count) {  // as render's last line; with several runs, each run's frames named
        std::string list;
        for (const auto& [run, frames] : f.incomplete)
            list += (list.empty() ? "" : "; ") + (f.summary.size() > 1 ? "run " + std::to_string(run) + ": " : "") + frames;
        std::fprintf(stderr, "incomplete frames: %zu of %zu (%s)\n", f.incomplete_count, f.frames, list.c_str());
    }
    if (g_interrupted) {
        std::fprintf(stderr, "interrupted after %zu of %zu runs; the files hold the finished runs\n", f.done, p.mine);
        return 130;
    }
    if (!baseline.is_null()) return compare_and_report(baseline, f.results, o);
    return 0;
}

// An option this mode would ignore is an error that says so (GRAPHS --out was
// silently ignored).
void check_options_used(const Args& a, const BenchOptions& o) {
    const std::vector<std::string> rendering = {
        "experiment", "shard", "size", "time", "frames", "warmup", "set", "timing", "camera", "report", "no-images",
        "data", "mesh", "phantom", "time-array", "velocity-array", "time-step", "units", "streamlines", "pseudo-time",
        "allow-empty-frames", "plugin-dir", "trust-graph-plugins", "quiet"};
    auto all_but = [&](std::vector<std::string> keep) {
        std::vector<std::string> out = rendering;
        out.insert(out.end(), {"compare", "against", "threshold", "plots", "out", "merge"});
        std::erase_if(out, [&](const std::string& n) { return std::find(keep.begin(), keep.end(), n) != keep.end(); });
        return out;
    };
    if (!o.merge.empty()) {
        if (!o.graphs.empty()) throw UsageError("GRAPHS do nothing with --merge (it joins results folders; nothing is rendered)");
        a.unused_here(all_but({"merge", "out", "plots"}), "with --merge (it joins results folders; nothing is rendered)");
    }
    if (!o.against.empty()) {
        if (!o.graphs.empty()) throw UsageError("GRAPHS do nothing with --against (it compares two results files)");
        a.unused_here(all_but({"compare", "against", "threshold"}),
                      "with --against (it compares two results files; nothing is rendered)");
    }
    if (o.compare.empty()) a.unused_here({"threshold"}, "without --compare BASELINE.json");
    if (o.experiment.empty() && o.out.empty()) a.unused_here({"no-images"}, "without --out or --experiment (no images are written)");
}

int run(const std::vector<std::string>& argv) {
    Args a("bench",
           "Times graphs over the same data, camera, times and output sizes. For every graph and size it\n"
           "prints the per-pass table (median, p5, p95 in ms, share of the frame) and ends with a summary.\n"
           "--experiment runs a declared study (graphs/experiments/*.json: graphs, data sets, sizes, times,\n"
           "sweeps) and writes results.json (every frame, machine, GL renderer, command, graph hashes),\n"
           "summary.csv, frames.csv, passes.svg (stacked per-pass bars), sweep.svg and one image per run.\n"
           "--compare checks the results against a baseline results.json and exits 1 on a regression: a\n"
           "pass counts as slower only when its median grew by more than --threshold, as measured AND on the\n"
           "machine's own speed (a calibration workload timed beside every run), its per-frame samples lie\n"
           "apart from the baseline's (middle halves, rank test), so a busy machine or noise is not flagged.\n"
           "--set GRAPH:NAME=VALUE goes to that graph only (so other graphs need not know NAME); plain\n"
           "--set NAME=VALUE goes to every graph, and a graph without NAME is an error.\n"
           "Ctrl-C stops after the run in progress; the files then hold every finished run.");
    BenchOptions o;
    o.declare(a);
    a.example("pathlet bench variant1_lineao,isl --size 1280x720,1920x1080",
              "the study's comparison on the built-in phantom with a 1 s pathlet window")
        .example("pathlet bench variant1_lineao --set window=0", "every line drawn (no time window)")
        .example("pathlet bench variant3_geomfade,variant3_geomfade --set 2:fade_measure=arc_length",
                 "one graph twice, side by side: taper measured in time (1) and in arc length (2)")
        .example("pathlet bench --experiment graphs/experiments/table3_variants.json --out out/t3",
                 "the study's Table 3 with plots in out/t3")
        .example("pathlet bench --experiment graphs/experiments/table3_variants.json --compare base/results.json",
                 "the same, checked against an earlier run (exit 1 on a regression)")
        .example("pathlet bench --experiment E.json --shard 0/3 --out s0   (then s1, s2; then --merge s0 --merge s1 "
                 "--merge s2 --out all)",
                 "split over three machines (see scripts/slurm/)");
    if (!a.parse(argv)) return 0;
    check_options_used(a, o);

    if (!o.merge.empty()) return merge(o);
    if (!o.against.empty()) {
        if (o.compare.empty()) throw UsageError("--against needs --compare BASELINE.json");
        return compare_and_report(text::read_json_file(o.compare, "the baseline"),
                                  text::read_json_file(o.against, "the results"), o);
    }
    json baseline;
    if (!o.compare.empty()) baseline = text::read_json_file(o.compare, "the baseline");  // before the run

    Runtime rt;
    o.plugins.load(rt);
    o.sets = rt.user_sets(o.sets);  // hook paths the user gave, before the plan takes them
    const Plan plan = make_plan(o, argv);
    g_interrupted = 0;
    struct RestoreSignal {
        void (*old)(int);
        ~RestoreSignal() { std::signal(SIGINT, old); }
    } restore{std::signal(SIGINT, on_sigint)};
    Finished f;
    try {
        // Every graph's plugin folders, trusted, before any work.
        for (const auto& [label, g] : plan.how.graphs.items()) rt.load_graph_plugins(parse_graph_file(g["path"].get<std::string>()));
        f = run_plan(o, plan, rt);
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
    return report(o, plan, f, baseline);
}

PATHLET_COMMAND("bench", "time graphs or run experiments: per-pass tables, reports, plots, regression checks", run);

}  // namespace
}  // namespace pathlet::cli
