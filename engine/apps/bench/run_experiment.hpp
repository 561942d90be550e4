// Running an experiment: every run (graph x sweep value x size x data set) of one shard through
// the renderer, into a report (results.json's content). Shared by `pathlet bench` and the
// Python module, so both measure and record the same way; the caller loads the data, writes
// files and shows progress through the hooks.
#pragma once

#include "experiment.hpp"
#include "shard.hpp"

#include "profiler/profiler.hpp"
#include "runtime.hpp"

#include <pathlet/scene.hpp>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace pathlet::cli::bench {

// An experiment's data set, loaded as --phantom or --data/--mesh would load it (quietly).
Scene load_data_set(const DataSet& ds);

// Per graph label: the graph as given, its resolved file and its hash. Throws
// std::runtime_error ("ORIGIN: /graphs/I: no graph file ...") for a graph that is not there:
// call it before any work.
nlohmann::json graph_info(const Experiment& e, const std::string& origin);

struct RunDone {
    const Run& run;
    const Profiler& profiler;
    const Scene& scene;
    size_t done, mine;  // runs of this shard finished, and in all
    const std::vector<size_t>& incomplete_frames;  // the run's (RenderResult::incomplete_frames)
    size_t frames;                                 // the run's frames
};

struct ExperimentHooks {
    // The scene of data set `index` (Experiment::data; the caller's own when that is empty).
    std::function<Scene(size_t index)> load_data;
    // After the header is made (done == nullptr) and after every run: the report so far.
    std::function<void(const nlohmann::json& report, const RunDone* done)> on_report;
    std::function<bool()> stop;  // asked before every run (Ctrl-C); may be empty
};

struct ExperimentSettings {
    Shard shard;
    TimingBackend timing = TimingBackend::Auto;
    std::string command;         // the header's "command"
    nlohmann::json graphs;       // graph_info(e, ...)
    std::string image_dir;       // "": no representative images; else images/run<k>/... under it
};

// Runs this shard's runs in plan order. Throws GraphError (a graph or --set is wrong) and
// whatever rendering throws; the report given to on_report before that is complete so far.
nlohmann::json run_experiment(Runtime& rt, const Experiment& e, const ExperimentSettings& s,
                              const ExperimentHooks& hooks);

}  // namespace pathlet::cli::bench
