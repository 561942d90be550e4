// results.json, the record of a bench run, in one place: its header (what was planned, on
// which machine), the data sets, one entry per finished run, and the merge of shard results.
// report.hpp derives every other file (CSV, SVG) from it.
//
//   {"experiment", "description", "command", "machine": {host, cpu, cores}, "gl_renderer",
//    "graphs": {label: {graph, path, fnv1a64}}, "sizes", "time" ("" = the middle of each data
//    set's span), "frames", "warmup", "sweep_param", "planned_runs", "complete",
//    "shard": {index, count} (a shard only), "timing_backend",
//    "calibration": {workload, median_ms} (the machine's speed over all runs: bench/calibration.hpp),
//    "data": [{source, lines, points, mesh_triangles, time (as rendered: "T" or "A:B:STEP"),
//              gpu_points {layout, bytes, bytes_per_point, positions, attributes, lod, chunks, summary}}],
//    "runs": [{"meta": {index, label, graph_label, graph, graph_path, size, sweep_value, sets, data,
//                       renderer, image?}, profiler summary..., "frames": [...],
//              "calibration": {before_ms: [...], after_ms: [...], median_ms}}]}
#pragma once

#include "bench/experiment.hpp"
#include "bench/shard.hpp"
#include "profiler/profiler.hpp"
#include "renderer.hpp"

#include <pathlet/scene.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

class Results {
public:
    Results(const Experiment& e, const std::string& command, const std::string& gl_renderer, const nlohmann::json& graphs,
            size_t planned_runs, const Shard& shard);
    // The data set the next runs draw, at `time`.
    void add_data(const Scene& scene, const TimeRange& time);
    // A finished run: its place in the plan, what it drew, its timings and representative image.
    void add_run(size_t index, const Run& run, const ExperimentGraph& g, const std::string& graph_path,
                 const std::vector<std::string>& sets, const std::string& data, const Profiler& p, const std::string& image);
    // The calibration workload's samples timed just before and after the last run added
    // (bench/calibration.hpp): the run's "calibration" and the header's median over all runs.
    void add_calibration(const std::string& workload, const std::vector<double>& before_ms,
                         const std::vector<double>& after_ms);
    void set_complete(bool c) { j_["complete"] = c; }
    const nlohmann::json& doc() const { return j_; }  // what results.json holds

private:
    nlohmann::json j_;
};

// A graph of the header's "graphs": {graph, path, fnv1a64 (FNV-1a 64 of the file's bytes)}.
nlohmann::json graph_entry(const std::string& graph, const std::string& path);

// Shard results (folder, results.json) joined into what one unsharded run writes; images are
// copied into out_dir. Throws std::runtime_error for parts of another experiment or a run twice.
nlohmann::json merge_results(const std::vector<std::pair<std::string, nlohmann::json>>& parts, const std::string& out_dir);

}  // namespace pathlet::cli::bench
