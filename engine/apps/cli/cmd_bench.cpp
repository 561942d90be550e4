// pathlet bench GRAPH... | --experiment FILE | --merge DIR... | --compare BASE [--against CUR]:
// the same data, camera, times and sizes through several graphs; per-pass tables, report files,
// plots, shards for clusters and a noise-aware regression check against a baseline.
// A bench is three steps: plan (the experiment, from a file or the command line, checked before
// any work), run (every run of this shard, results written after each) and report (the summary
// table, the files, the comparison with a baseline). results.json's layout: bench/results.hpp.
#include "bench/compare.hpp"
#include "bench/experiment.hpp"
#include "bench/report.hpp"
#include "bench/results.hpp"
#include "bench/shard.hpp"
#include "commands.hpp"
#include "common_options.hpp"
#include "graph_errors.hpp"
#include "progress.hpp"
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
    Given<std::string> sizes{"1280x720"}, time{"9"};
    Given<int> frames{10}, warmup{3};
    TimingBackend timing = TimingBackend::Auto;
    bool no_images = false, quiet = false;
    PluginOptions plugins;
    SceneOptions data;

    void declare(Args& a) {
        a.positional("GRAPHS", graphs, "comma-separated graph files or shipped graph names (e.g. variant1_lineao,isl)", false)
            .option("experiment", experiment, "FILE", "run an experiment file (schema: graphs/schema/pathlet-experiment.schema.json)")
            .option("out", out, "DIR", "where --experiment or --merge writes (default out/bench/<experiment name>)")
            .option("shard", shard, "I/N", "do part I (0-based) of N of the runs: run k belongs to shard k % N")
            .multi("merge", merge, "DIR", "join shard results folders (repeat) into --out; no rendering")
            .option("compare", compare, "BASELINE.json", "compare with a baseline results.json; exit 1 on a regression")
            .option("against", against, "RESULTS.json", "with --compare: compare these results instead of running")
            .option("threshold", threshold, "FRACTION",
                    "--compare: relative slow-down that counts (0.5 = 50 %; on this shared 2-core machine plain\n"
                    "re-runs drift by up to ~40 %, so use 0.1 only on a quiet, dedicated node)")
            .option("size", sizes, "WxH[,WxH...]", "output sizes to measure (overrides the experiment's)")
            .option("time", time, "T|A:B:STEP", "animation time(s) rendered (overrides the experiment's)")
            .option("frames", frames, "N", "measured frames per time, after warm-up (overrides the experiment's)")
            .option("warmup", warmup, "N", "frames before timing starts (overrides the experiment's)")
            .multi("set", sets, "[GRAPH:]NAME=VALUE",
                   "override a variable or pass parameter: in every graph, or with GRAPH: (a graph as listed or its "
                   "label, or its position 1, 2, ...) in that one only; unknown names are errors");
        declare_timing(a, timing);
        declare_camera(a, camera);
        a.option("report", report, "PREFIX", "write PREFIX.csv and PREFIX.json with every pass of every run")
            .flag("no-images", no_images, "--experiment: no representative image per run")
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
    std::printf("compare against %s (regression: >%.0f %% slower and p5..p95 ranges apart)\n%s", o.compare.c_str(),
                o.threshold * 100, c.table.c_str());
    for (const auto& m : c.missing) std::printf("  not in the current results: %s\n", m.c_str());
    std::printf("%d compared, %d regressions, %d faster\n", c.compared, c.regressions, c.improvements);
    if (c.compared == 0) {
        std::fprintf(stderr, "error: nothing in common with the baseline (different graphs or sizes?)\n");
        return 1;
    }
    return c.regressions > 0 ? 1 : 0;
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
    bool from_file = false, images = false;
    RenderOptions base;  // what every run shares
    Shard shard;
    std::vector<bench::Run> runs;
    size_t mine = 0;     // runs of this shard
    json graphs;         // results.json's "graphs"
    std::string out_dir; // --experiment's folder ("" for a plain bench)
};

Plan make_plan(const BenchOptions& o) {
    Plan p;
    p.from_file = !o.experiment.empty();
    if (p.from_file == !o.graphs.empty())
        throw UsageError(p.from_file ? "give either GRAPHS or --experiment, not both" : "missing GRAPHS (or --experiment FILE)");
    Experiment& e = p.e;
    e = p.from_file ? with_command_line(bench::load_experiment(o.experiment), o) : experiment_from_args(o);
    if (e.frames < 1 || e.warmup < 0) throw UsageError("--frames must be >= 1 and --warmup >= 0");
    try {
        for (const auto& s : e.sizes) parse_size(s);
        p.base.time = parse_time_range(e.time);
    } catch (const std::invalid_argument& ex) {
        throw UsageError(e.name + ": " + ex.what());
    }
    if (o.shard) p.shard = *o.shard;
    p.base.timing = o.timing;
    p.base.repeat = e.frames;
    p.base.warmup = e.warmup;
    p.base.camera_path = e.camera;
    p.base.orbit_deg_per_s = e.orbit_deg_per_s;
    p.base.write_images = false;
    p.base.quiet = true;

    p.graphs = json::object();
    for (size_t gi = 0; gi < e.graphs.size(); ++gi) {
        const std::string path = resolve_graph_path(e.graphs[gi].graph);
        if (!fs::is_regular_file(path))
            throw std::runtime_error((p.from_file ? o.experiment + ": /graphs/" + std::to_string(gi) + ": " : "") +
                                     "no graph file or shipped graph named '" + e.graphs[gi].graph + "'");
        p.graphs[e.graphs[gi].label] = bench::graph_entry(e.graphs[gi].graph, path);
    }
    if (p.from_file) {
        p.out_dir = !o.out.empty() ? o.out
                                   : "out/bench/" + e.name +
                                         (p.shard.active() ? "/shard" + std::to_string(p.shard.index) + "of" +
                                                                 std::to_string(p.shard.count)
                                                           : "");
        check_output_dir(p.out_dir, "experiment results (--out)");
    }
    if (!o.report.empty()) check_output_file(o.report + ".csv", "the report (--report)");
    p.images = p.from_file && !o.no_images;
    p.runs = bench::plan_runs(e);
    for (size_t k = 0; k < p.runs.size(); ++k) p.mine += p.shard.owns(k);
    return p;
}

// ---- run --------------------------------------------------------------------------------
// Runs the plan's runs of this shard; writes the result files after each, so an interrupted or
// failed bench keeps what it finished.
class BenchRun {
public:
    BenchRun(const BenchOptions& o, const Plan& p, Runtime& rt, const std::string& command)
        : o_(o), p_(p), rt_(rt), results_(p.e, command, rt.gl->renderer(), p.graphs, p.runs.size(), p.shard) {}

    // 0, or 1 when a graph failed (reported).
    int run_all();
    const bench::Results& results() const { return results_; }
    const std::vector<std::pair<std::string, Profiler::Stats>>& summary() const { return summary_; }
    const std::optional<Scene>& scene() const { return scene_; }
    size_t done() const { return done_; }
    void write_files() const;

private:
    void load_data(size_t d);
    std::string representative_image(size_t k, const RenderOptions& opt);

    const BenchOptions& o_;
    const Plan& p_;
    Runtime& rt_;
    bench::Results results_;
    std::vector<std::pair<std::string, Profiler::Stats>> summary_;
    std::optional<Scene> scene_;
    size_t scene_of_ = size_t(-1), done_ = 0;
};

void BenchRun::write_files() const {
    if (p_.from_file) bench::write_report_dir(p_.out_dir, results_.doc());
    if (!o_.report.empty()) {
        write_file_atomic(o_.report + ".csv", bench::summary_csv(results_.doc()));
        write_file_atomic(o_.report + ".json", results_.doc().dump(1));
    }
}

void BenchRun::load_data(size_t d) {
    scene_.reset();
    if (p_.e.data.empty()) {
        scene_ = o_.data.load(true);
    } else {
        SceneOptions ds;  // an experiment's data set, read with the default arrays
        ds.data = p_.e.data[d].file;
        ds.mesh = p_.e.data[d].mesh;
        if (!p_.e.data[d].phantom.empty()) ds.phantom.value = p_.e.data[d].phantom;
        scene_ = ds.load(true);
    }
    scene_of_ = d;
    results_.add_data(*scene_);
    for (double t : p_.base.time.times())  // an empty picture times nothing worth knowing
        if (t < scene_->lines.time_min() || t > scene_->lines.time_max()) {
            std::fprintf(stderr, "warning: time %g s is outside %s's %g..%g s: few or no lines are drawn\n", t,
                         scene_->source.c_str(), scene_->lines.time_min(), scene_->lines.time_max());
            break;
        }
}

// What the time bought: one frame of the run, at the first time, written; its path relative to
// the results folder.
std::string BenchRun::representative_image(size_t k, const RenderOptions& opt) {
    RenderOptions io = opt;
    io.time = TimeRange{p_.base.time.times().front(), p_.base.time.times().front()};
    io.repeat = 1;
    io.warmup = 0;
    io.write_images = true;
    io.out_dir = p_.out_dir + "/images/run" + std::to_string(k);
    for (const auto& f : render(rt_, *scene_, io).files)
        if (fs::path(f).extension() == ".png") return fs::relative(f, p_.out_dir).generic_string();
    return "";
}

int BenchRun::run_all() {
    results_.set_complete(p_.mine == 0);
    write_files();  // a shard with no runs (N > runs) still leaves its (empty) results
    Progress progress("runs", p_.mine, o_.quiet);
    for (size_t k = 0; k < p_.runs.size() && !g_interrupted; ++k) {
        if (!p_.shard.owns(k)) continue;
        const bench::Run& run = p_.runs[k];
        if (scene_of_ != run.data) load_data(run.data);
        const auto& g = p_.e.graphs[run.graph];
        RenderOptions opt = p_.base;
        opt.graph_path = resolve_graph_path(g.graph);
        opt.sets = p_.e.sets;
        opt.sets.insert(opt.sets.end(), g.sets.begin(), g.sets.end());
        if (!p_.e.sweep.param.empty()) opt.sets.push_back(p_.e.sweep.param + "=" + run.sweep_value);
        opt.size = parse_size(run.size);
        RenderResult r;
        std::string image;
        try {
            r = render(rt_, *scene_, opt);
            if (p_.images) image = representative_image(k, opt);
        } catch (const GraphError& ex) {
            return report_graph_error(ex, rt_);
        }
        const std::string title = run.label + " — " + run.size + ", " + std::to_string(scene_->lines.line_count()) + " lines";
        if (!o_.quiet || !p_.from_file) std::printf("%s\n", r.profiler.table(title).c_str());
        summary_.push_back({run.label + "  " + run.size, r.profiler.frame_ms()});
        results_.add_run(k, run, g, opt.graph_path, opt.sets, scene_->source, r.profiler, image);
        results_.set_complete(++done_ == p_.mine);
        write_files();
        progress.update(done_, run.label);
    }
    progress.finish(std::to_string(done_) + " runs");
    return 0;
}

// ---- report -----------------------------------------------------------------------------
int report(const BenchOptions& o, const Plan& p, const BenchRun& b, const json& baseline) {
    std::printf("summary (%s; %s)\n", b.results().doc().value("gl_renderer", "").c_str(),
                b.scene() ? b.scene()->source.c_str() : "");
    std::printf("  %-40s %10s %10s %10s %8s\n", "run", "median ms", "p5 ms", "p95 ms", "fps");
    for (const auto& [label, f] : b.summary())
        std::printf("  %-40s %10.2f %10.2f %10.2f %8.1f\n", label.c_str(), f.median, f.p5, f.p95,
                    f.median > 0 ? 1000.0 / f.median : 0.0);
    if (p.from_file) std::fprintf(stderr, "wrote %s/results.json, summary.csv, frames.csv and plots\n", p.out_dir.c_str());
    if (!o.report.empty()) std::fprintf(stderr, "wrote %s.csv and %s.json\n", o.report.c_str(), o.report.c_str());
    if (g_interrupted) {
        std::fprintf(stderr, "interrupted after %zu of %zu runs; the files hold the finished runs\n", b.done(), p.mine);
        return 130;
    }
    if (!baseline.is_null()) return compare_and_report(baseline, b.results().doc(), o);
    return 0;
}

int run(const std::vector<std::string>& argv) {
    Args a("bench",
           "Times graphs over the same data, camera, times and output sizes. For every graph and size it\n"
           "prints the per-pass table (median, p5, p95 in ms, share of the frame) and ends with a summary.\n"
           "--experiment runs a declared study (graphs/experiments/*.json: graphs, data sets, sizes, times,\n"
           "sweeps) and writes results.json (every frame, machine, GL renderer, command, graph hashes),\n"
           "summary.csv, frames.csv, passes.svg (stacked per-pass bars), sweep.svg and one image per run.\n"
           "--compare checks the results against a baseline results.json and exits 1 on a regression: a\n"
           "pass counts as slower only when its median grew by more than --threshold AND its p5..p95 range\n"
           "lies wholly above the baseline's, so re-runs on a noisy machine are not flagged.\n"
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

    if (!o.merge.empty()) return merge(o);
    if (!o.against.empty()) {
        if (o.compare.empty()) throw UsageError("--against needs --compare BASELINE.json");
        return compare_and_report(text::read_json_file(o.compare, "the baseline"),
                                  text::read_json_file(o.against, "the results"), o);
    }
    json baseline;
    if (!o.compare.empty()) baseline = text::read_json_file(o.compare, "the baseline");  // before the run

    const Plan plan = make_plan(o);
    Runtime rt;
    o.plugins.load(rt);
    try {  // every graph's plugin folders, trusted, before any work
        for (const auto& [label, g] : plan.graphs.items()) rt.load_graph_plugins(parse_graph_file(g["path"].get<std::string>()));
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
    rt.ensure_gl(true);
    std::vector<std::string> command = {"pathlet", "bench"};
    command.insert(command.end(), argv.begin(), argv.end());
    BenchRun bench(o, plan, rt, text::shell_command(command));
    g_interrupted = 0;
    auto old_handler = std::signal(SIGINT, on_sigint);
    const int failed = bench.run_all();
    std::signal(SIGINT, old_handler);
    return failed ? failed : report(o, plan, bench, baseline);
}

PATHLET_COMMAND("bench", "time graphs or run experiments: per-pass tables, reports, plots, regression checks", run);

}  // namespace
}  // namespace pathlet::cli
