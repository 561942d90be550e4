// What every command needs: the pass registry filled from the plugin search path, and
// (for commands that draw) a headless GL context.
#pragma once

#include "gl_context.hpp"
#include "graph/graph_model.hpp"
#include "pass_registry.hpp"
#include "plugin_host.hpp"

#include <memory>
#include <string>
#include <vector>

namespace pathlet {

struct Runtime {
    PassRegistry registry;
    PluginHost host{registry};
    std::unique_ptr<GlContext> gl;

    // Loads every plugin on the search path; problems are kept in host.problems().
    void load_plugins(const std::vector<std::string>& extra_dirs);
    // Loads the plugin folders a graph file names ("plugin_dirs"), once each.
    void load_graph_plugins(const GraphFile& g);
    // Parses a graph file, loads its plugin folders and applies --set overrides (GraphError
    // with every problem): what render, view and graph do before compiling.
    GraphFile load_graph(const std::string& path, const std::vector<std::string>& sets);
    // Creates the GL context (once) and prints its renderer line unless quiet.
    GlContext& ensure_gl(bool quiet);
    // Text listing plugin problems, to append to "unknown pass type" errors.
    std::string plugin_problems_note() const;
};

}  // namespace pathlet
