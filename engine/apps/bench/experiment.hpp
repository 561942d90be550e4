// An experiment file (graphs/experiments/*.json): which graphs, sizes, times, frames and sweep
// `pathlet bench --experiment` runs. Schema: graphs/schema/pathlet-experiment.schema.json.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

struct ExperimentGraph {
    std::string graph;              // file or shipped name
    std::string label;              // shown in tables and plots (default: graph)
    std::vector<std::string> sets;  // NAME=VALUE for this graph only
};

struct Sweep {
    std::string param;               // a --set name, e.g. "lineao.samples" or "window"
    std::vector<std::string> values; // as --set values
};

// A data set: a built-in phantom preset or a pathline file (with an optional wall mesh).
struct DataSet {
    std::string label;             // default: the preset or file stem
    std::string phantom, file, mesh;
};

struct Experiment {
    std::string name, description;
    std::vector<ExperimentGraph> graphs;
    std::vector<std::string> sizes{"1280x720"};  // "WxH"
    std::string time;                            // "T" or "A:B:STEP"; "": the middle of each data set's span
    int frames = 10, warmup = 3;
    std::vector<std::string> sets;  // for every graph
    std::string camera;             // camera path file, relative to the experiment file; "" = frame the data
    double orbit_deg_per_s = 0.0;
    Sweep sweep;                    // empty param = no sweep
    std::vector<DataSet> data;      // empty: the command line's --data/--phantom
};

// One measured configuration: graph x sweep value x size.
struct Run {
    size_t data = 0;   // index into Experiment::data (0 when it is empty)
    size_t graph = 0;
    std::string sweep_value;  // "" without a sweep
    std::string size;
    std::string label;  // graph label, sweep value, data set (filled by plan_runs)
};

// Throws DataError "FILE: /json/pointer: message (did you mean 'x'?)"; the file is read with
// the limits of graph files (util/text.hpp: size, nesting, numbers).
Experiment load_experiment(const std::string& path);
Experiment parse_experiment(const nlohmann::json& j, const std::string& origin);
// Every run in a fixed order (data set, graph, sweep value, size); shards pick runs by index.
std::vector<Run> plan_runs(const Experiment& e);

}  // namespace pathlet::cli::bench
