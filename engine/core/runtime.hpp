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
    // --trust-graph-plugins: this run loads the plugin folders graph files name, trusted or not.
    bool trust_graph_plugins = false;

    // Loads every plugin on the search path (folders the user chose for this run, so trusted);
    // problems are kept in host.problems().
    void load_plugins(const std::vector<std::string>& extra_dirs);
    // The plugin folders a graph file names ("plugin_dirs") that hold plugins but are not
    // trusted (plugin_trust.hpp): on the search path, in the trust file, or --trust-graph-plugins.
    std::vector<GraphFile::UntrustedDir> untrusted_plugin_dirs(const GraphFile& g) const;
    // Loads the plugin folders a graph file names, once each. When one of them is not trusted,
    // nothing is loaded: GraphError naming the graph, the folder, its plugin files and the
    // command that trusts it.
    void load_graph_plugins(const GraphFile& g);
    // validate: loads the trusted folders only and notes the others in g.untrusted_plugin_dirs,
    // so an unknown pass type is reported as possibly theirs.
    void load_trusted_graph_plugins(GraphFile& g);
    // Parses a graph file, loads its plugin folders and applies --set overrides (GraphError
    // with every problem): what render, view and graph do before compiling.
    GraphFile load_graph(const std::string& path, const std::vector<std::string>& sets);
    // Creates the GL context (once) and prints its renderer line unless quiet.
    GlContext& ensure_gl(bool quiet);
    // Text listing plugin problems and skipped files, to append to "unknown pass type" errors.
    std::string plugin_problems_note() const;

private:
    std::vector<std::string> run_trusted_;  // canonical search-path folders
};

}  // namespace pathlet
