// pathlet bench GRAPH... | --experiment FILE | --merge DIR... | --compare BASE [--against CUR]:
// the same data, camera, times and sizes through several graphs; per-pass tables, report files,
// plots, shards for clusters and a noise-aware regression check against a baseline.
#include "args.hpp"
#include "bench/compare.hpp"
#include "bench/experiment.hpp"
#include "bench/plots.hpp"
#include "bench/report.hpp"
#include "bench/run_experiment.hpp"
#include "bench/shard.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "util/atomic_file.hpp"
#include "util/output_check.hpp"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace pathlet::cli {
namespace {

namespace fs = std::filesystem;
using bench::Experiment;

volatile std::sig_atomic_t g_interrupted = 0;
void on_sigint(int) { g_interrupted = 1; }

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

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string tok;
    while (std::getline(in, tok, sep))
        if (!tok.empty()) out.push_back(tok);
    return out;
}

json read_json(const std::string& path, const std::string& what) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open " + what);
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": " + what + " is not valid JSON: " + e.what());
    }
}

std::string command_line(const std::vector<std::string>& argv) {
    std::string s = "pathlet bench";
    for (const auto& a : argv) {
        bool plain = !a.empty() && a.find_first_of(" \t'\"\\$`*?") == std::string::npos;
        s += " " + (plain ? a : "'" + a + "'");
    }
    return s;
}

// Positional GRAPHS and --set turned into an experiment, so both forms run the same code.
Experiment experiment_from_args(const Args& a) {
    Experiment e;
    e.name = "bench";
    const std::vector<std::string> graphs = split(a.pos("GRAPHS"), ',');
    const std::vector<std::string> sets = a.all("set");
    for (size_t gi = 0; gi < graphs.size(); ++gi) sets_for(sets, graphs, gi);  // bad qualifiers: before any work
    std::set<std::string> labels;
    for (size_t gi = 0; gi < graphs.size(); ++gi) {
        bench::ExperimentGraph g{graphs[gi], graphs[gi], sets_for(sets, graphs, gi)};
        for (const auto& s : g.sets)  // label with the overrides only this graph gets
            if (std::find(sets.begin(), sets.end(), s) == sets.end()) g.label += " [" + s + "]";
        if (!labels.insert(g.label).second) g.label += " #" + std::to_string(gi + 1);
        e.graphs.push_back(g);
    }
    return e;
}

int compare_and_report(const json& baseline, const json& current, const Args& a) {
    const double threshold = a.number("threshold");
    if (!(threshold > 0)) throw UsageError("--threshold must be > 0 (0.5 = 50 % slower)");
    bench::CompareResult c = bench::compare_reports(baseline, current, threshold);
    std::printf("compare against %s (regression: >%.0f %% slower and p5..p95 ranges apart)\n%s",
                a.get("compare").c_str(), threshold * 100, c.table.c_str());
    for (const auto& m : c.missing) std::printf("  not in the current results: %s\n", m.c_str());
    std::printf("%d compared, %d regressions, %d faster\n", c.compared, c.regressions, c.improvements);
    if (c.compared == 0) {
        std::fprintf(stderr, "error: nothing in common with the baseline (different graphs or sizes?)\n");
        return 1;
    }
    return c.regressions > 0 ? 1 : 0;
}

// --merge: shard results joined into the files one unsharded run writes.
int merge(const Args& a) {
    if (!a.has("out")) throw UsageError("--merge needs --out DIR for the joined results");
    const std::string out = a.get("out");
    check_output_dir(out, "merged results (--out)");
    json merged;
    std::map<size_t, json> runs;
    for (const auto& dir : a.all("merge")) {
        const json part = read_json(dir + "/results.json", "shard results");
        if (merged.is_null()) merged = part;
        else if (part.value("experiment", "") != merged.value("experiment", "") ||
                 part.value("planned_runs", 0) != merged.value("planned_runs", 0))
            throw std::runtime_error(dir + "/results.json: from another experiment than " + a.all("merge").front());
        for (const json& r : part.at("runs")) {
            size_t k = r.at("meta").at("index").get<size_t>();
            if (runs.count(k)) throw std::runtime_error(dir + ": run " + std::to_string(k) + " is in two shards");
            json copy = r;
            if (copy["meta"].contains("image") && copy["meta"]["image"].is_string()) {
                const std::string rel = copy["meta"]["image"];
                fs::create_directories((fs::path(out) / rel).parent_path());
                fs::copy_file(fs::path(dir) / rel, fs::path(out) / rel, fs::copy_options::overwrite_existing);
            }
            runs[k] = copy;
        }
    }
    merged.erase("shard");
    merged["runs"] = json::array();
    for (auto& [k, r] : runs) merged["runs"].push_back(r);
    const size_t planned = merged.value("planned_runs", size_t(0));
    merged["complete"] = runs.size() == planned;
    bench::write_report_dir(out, merged);
    std::fprintf(stderr, "merged %zu of %zu runs into %s\n", runs.size(), planned, out.c_str());
    if (a.has("plots"))
        if (const std::string err = bench::write_matplotlib_plots(out); !err.empty()) {
            std::fprintf(stderr, "error: --plots: %s\n", err.c_str());
            return 1;
        }
    if (runs.size() != planned) {
        std::fprintf(stderr, "error: %zu runs missing (a shard failed or was not listed)\n", planned - runs.size());
        return 1;
    }
    return 0;
}

Scene load_data_set(const Args& cli, const Experiment& e, size_t d) {
    if (e.data.empty()) return load_scene(cli, true);
    return bench::load_data_set(e.data[d]);
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
    a.positional("GRAPHS", "comma-separated graph files or shipped graph names (e.g. variant1_lineao,isl)", false)
        .option("experiment", "FILE", "", "run an experiment file (schema: graphs/schema/pathlet-experiment.schema.json)")
        .option("out", "DIR", "", "where --experiment or --merge writes (default out/bench/<experiment name>)")
        .option("shard", "I/N", "", "do part I (0-based) of N of the runs: run k belongs to shard k % N")
        .multi("merge", "DIR", "join shard results folders (repeat) into --out; no rendering")
        .option("compare", "BASELINE.json", "", "compare with a baseline results.json; exit 1 on a regression")
        .option("against", "RESULTS.json", "", "with --compare: compare these results instead of running")
        .option("threshold", "FRACTION", "0.5",
                "--compare: relative slow-down that counts (0.5 = 50 %; on this shared 2-core machine plain\n"
                "re-runs drift by up to ~40 %, so use 0.1 only on a quiet, dedicated node)")
        .option("size", "WxH[,WxH...]", "1280x720", "output sizes to measure (overrides the experiment's)")
        .option("time", "T|A:B:STEP", "9", "animation time(s) rendered (overrides the experiment's)")
        .option("frames", "N", "10", "measured frames per time, after warm-up (overrides the experiment's)")
        .option("warmup", "N", "3", "frames before timing starts (overrides the experiment's)")
        .multi("set", "[GRAPH:]NAME=VALUE",
               "override a variable or pass parameter: in every graph, or with GRAPH: (a graph as listed or its "
               "label, or its position 1, 2, ...) in that one only; unknown names are errors")
        .option("timing", "auto|gpu|finish", "auto", "timing backend (auto: finish on llvmpipe, timestamps on a GPU)")
        .option("camera", "FILE", "", "camera path JSON (default: frame the data)")
        .option("report", "PREFIX", "", "write PREFIX.csv and PREFIX.json with every pass of every run")
        .flag("no-images", "--experiment: no representative image per run")
        .flag("plots", "--experiment, --merge: also PNG and PDF figures with Matplotlib (python3 -m pathlet.plot)")
        .flag("quiet", "no progress line")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
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

    if (!a.all("merge").empty()) return merge(a);
    if (a.has("against")) {
        if (!a.has("compare")) throw UsageError("--against needs --compare BASELINE.json");
        return compare_and_report(read_json(a.get("compare"), "the baseline"), read_json(a.get("against"), "the results"), a);
    }
    json baseline;
    if (a.has("compare")) baseline = read_json(a.get("compare"), "the baseline");  // before the run

    const bool from_file = a.has("experiment");
    if (from_file == !a.pos("GRAPHS").empty())
        throw UsageError(from_file ? "give either GRAPHS or --experiment, not both" : "missing GRAPHS (or --experiment FILE)");
    if (a.has("plots") && !from_file) throw UsageError("--plots needs --experiment (or --merge): figures of a results folder");
    Experiment e = from_file ? bench::load_experiment(a.get("experiment")) : experiment_from_args(a);
    std::vector<std::string> cli_sets;  // --set on top of an experiment file, qualified by label
    if (from_file) {
        std::vector<std::string> labels;
        for (const auto& g : e.graphs) labels.push_back(g.label);
        for (size_t gi = 0; gi < e.graphs.size(); ++gi) {
            auto own = sets_for(a.all("set"), labels, gi);
            e.graphs[gi].sets.insert(e.graphs[gi].sets.end(), own.begin(), own.end());
        }
    }
    if (!from_file || a.has("size")) e.sizes = split(a.get("size"), ',');
    if (!from_file || a.has("time")) e.time = a.get("time");
    if (!from_file || a.has("frames")) e.frames = int(a.integer("frames"));
    if (!from_file || a.has("warmup")) e.warmup = int(a.integer("warmup"));
    if (a.has("camera")) e.camera = a.get("camera");
    // Data on the command line replaces the experiment's data sets (a quick run on other data).
    if (a.has("data") || a.has("phantom") || a.has("mesh")) e.data.clear();
    if (e.frames < 1 || e.warmup < 0) throw UsageError("--frames must be >= 1 and --warmup >= 0");

    Shard shard;
    bench::ExperimentSettings how;
    try {
        for (const auto& s : e.sizes) parse_size(s);
        parse_time_range(e.time);
        how.timing = parse_timing_backend(a.get("timing"));
        if (a.has("shard")) shard = parse_shard(a.get("shard"));
    } catch (const std::invalid_argument& ex) {
        throw UsageError(e.name + ": " + ex.what());
    }
    how.shard = shard;
    how.command = command_line(argv);
    // Graphs must exist, outputs must be writable: both before any work.
    how.graphs = bench::graph_info(e, from_file ? a.get("experiment") : "");
    std::string out_dir;
    if (from_file) {
        out_dir = a.has("out") ? a.get("out")
                               : "out/bench/" + e.name +
                                     (shard.active() ? "/shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count) : "");
        check_output_dir(out_dir, "experiment results (--out)");
    }
    if (a.has("report")) check_output_file(a.get("report") + ".csv", "the report (--report)");
    if (from_file && !a.has("no-images")) how.image_dir = out_dir;

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));

    json report;
    auto write_outputs = [&]() {
        if (from_file) bench::write_report_dir(out_dir, report);
        if (a.has("report")) {
            write_file_atomic(a.get("report") + ".csv", bench::summary_csv(report));
            write_file_atomic(a.get("report") + ".json", report.dump(1));
        }
    };
    g_interrupted = 0;
    struct RestoreSignal {
        void (*old)(int);
        ~RestoreSignal() { std::signal(SIGINT, old); }
    } restore{std::signal(SIGINT, on_sigint)};
    size_t done = 0, mine = 0;
    const size_t planned = bench::plan_runs(e).size();
    for (size_t k = 0; k < planned; ++k) mine += shard.owns(k);
    Progress progress("runs", mine, a.has("quiet"));
    std::vector<std::pair<std::string, Profiler::Stats>> summary;
    std::string source;
    bench::ExperimentHooks hooks;
    hooks.load_data = [&](size_t d) { return load_data_set(a, e, d); };
    hooks.stop = [] { return g_interrupted != 0; };
    hooks.on_report = [&](const json& r, const bench::RunDone* run) {
        report = r;
        write_outputs();  // after every run: an interrupted experiment keeps what it finished
        if (!run) return;
        const std::string title = run->run.label + " — " + run->run.size + ", " +
                                  std::to_string(run->scene.lines.line_count()) + " lines";
        if (!a.has("quiet") || !from_file) std::printf("%s\n", run->profiler.table(title).c_str());
        summary.push_back({run->run.label + "  " + run->run.size, run->profiler.frame_ms()});
        source = run->scene.source;
        done = run->done;
        progress.update(done, run->run.label);
    };
    try {
        report = bench::run_experiment(rt, e, how, hooks);
    } catch (const GraphError& ex) {
        for (const auto& d : ex.diagnostics) std::fprintf(stderr, "%s\n", d.str().c_str());
        std::fprintf(stderr, "%s", rt.plugin_problems_note().c_str());
        return 1;
    }
    progress.finish(std::to_string(done) + " runs");

    std::printf("summary (%s; %s)\n", rt.gl->renderer().c_str(), source.c_str());
    std::printf("  %-40s %10s %10s %10s %8s\n", "run", "median ms", "p5 ms", "p95 ms", "fps");
    for (const auto& [label, f] : summary)
        std::printf("  %-40s %10.2f %10.2f %10.2f %8.1f\n", label.c_str(), f.median, f.p5, f.p95,
                    f.median > 0 ? 1000.0 / f.median : 0.0);
    if (from_file) std::fprintf(stderr, "wrote %s/results.json, summary.csv, frames.csv and plots\n", out_dir.c_str());
    if (a.has("plots"))
        if (const std::string err = bench::write_matplotlib_plots(out_dir); !err.empty()) {
            std::fprintf(stderr, "error: --plots: %s\n", err.c_str());
            return 1;
        }
    if (a.has("report")) std::fprintf(stderr, "wrote %s.csv and %s.json\n", a.get("report").c_str(), a.get("report").c_str());
    if (g_interrupted) {
        std::fprintf(stderr, "interrupted after %zu of %zu runs; the files hold the finished runs\n", done, mine);
        return 130;
    }
    if (!baseline.is_null()) return compare_and_report(baseline, report, a);
    return 0;
}

PATHLET_COMMAND("bench", "time graphs or run experiments: per-pass tables, reports, plots, regression checks", run);

}  // namespace
}  // namespace pathlet::cli
