// The graph behind `pathlet view`: loaded, compiled and set up like `render`, then changed
// while it runs. A parameter change re-runs only the changed passes' setup() when the graph's
// structure stays the same (Executor::reparam), else it rebuilds; a rebuild that fails (bad
// JSON, a shader error, an unknown type) keeps the last good graph running and remembers the
// error for the window. Knows the overrides as `--set` arguments, so the view can be
// reproduced with `render`.
#pragma once

#include "executor.hpp"
#include "graph/graph_model.hpp"
#include "profiler/profiler.hpp"
#include "runtime.hpp"

#include <pathlet/gpu_scene.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pathlet::view {

class ViewSession {
    struct Built {  // one loaded graph: file, compiled plan, profiler, running executor
        GraphFile g;
        CompiledGraph cg;
        std::unique_ptr<Profiler> prof;
        std::unique_ptr<Executor> exec;
    };

public:
    ViewSession(Runtime& rt, const GpuScene& scene, glm::ivec2 size, std::string graph_path,
                const std::vector<std::string>& sets);
    ~ViewSession();

    // Loads the graph file again (a new graph, or the same after an edit). False: the error is
    // in error() and the previous graph keeps running (none before: throws it instead).
    bool rebuild();
    bool switch_graph(const std::string& path);  // overrides of the old graph are dropped
    // Sets "NAME" (a graph variable or pass.param) to VALUE as --set would. False: error().
    bool set(const std::string& name, const std::string& value);

    Executor& executor() { return *cur_->exec; }
    const CompiledGraph& compiled() const { return cur_->cg; }
    const GraphFile& graph() const { return cur_->g; }
    Profiler& profiler() { return *cur_->prof; }
    const std::string& graph_path() const { return path_; }
    const std::string& error() const { return error_; }
    // The overrides in the order given, later ones replacing earlier ones of the same name.
    std::vector<std::string> sets() const;
    // Files to watch for hot reload: the graph and the shader folders of its passes.
    std::vector<std::string> watched_files() const;
    // The current value of a variable or pass.param as JSON (after overrides).
    json value(const std::string& name) const;

private:
    std::unique_ptr<Built> build(const std::vector<std::string>& sets) const;
    bool same_structure(const CompiledGraph& a, const CompiledGraph& b) const;

    Runtime& rt_;
    const GpuScene& scene_;
    glm::ivec2 size_;
    std::string path_;
    std::vector<std::pair<std::string, std::string>> overrides_;
    std::unique_ptr<Built> cur_;
    std::string error_;
};

}  // namespace pathlet::view
