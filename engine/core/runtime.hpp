// What every command needs: the pass registry filled from the plugin search path, and
// (for commands that draw) a headless GL context.
#pragma once

#include "gl_context.hpp"
#include "graph/graph_model.hpp"
#include "pass_registry.hpp"
#include "plugin_host.hpp"

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace pathlet {

struct Runtime {
    PassRegistry registry;
    PluginHost host{registry};
    std::unique_ptr<GlContext> gl;
    // --trust-graph-plugins: this run loads the plugin folders graph files name, trusted or not.
    bool trust_graph_plugins = false;
    // Hook files the user named by path on the command line or in Python (absolute, as
    // user_sets made them): the only files outside the shader path and a graph's folders that a
    // graph's hook may be (apply_overrides). An experiment file or a viewer script names hooks
    // as graph files do.
    std::set<std::string> user_files;

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
    // The user's own --set texts (the command line, Python's Graph.set) with the paths they give
    // hooks made the user's: PASS.HOOK=PATH, where HOOK is a hook parameter of a loaded pass
    // type (color_hook, width_hook), is absolute or relative to the current folder (a plain name
    // there only when that file exists; else it is a name on the shader path or next to the
    // graph), made absolute and added to user_files. std::invalid_argument for a path to no file.
    std::vector<std::string> user_sets(std::vector<std::string> sets);
    // Who gave a run's --set texts: the user (the command line, Python: user_sets applies) or a
    // file (an experiment, a viewer script: hooks by name, or files the user already named).
    enum class SetsFrom { user, file };
    // Parses a graph file, loads its plugin folders and applies --set overrides, which resolves
    // its hooks (GraphError with every problem): what every command does before compiling.
    // g.notes says what the author may not expect (a replaced hook's parameters dropped).
    GraphFile load_graph(const std::string& path, const std::vector<std::string>& sets, SetsFrom from = SetsFrom::file);
    // Creates the GL context (once) and prints its renderer line unless quiet.
    GlContext& ensure_gl(bool quiet);
    // Text listing plugin problems and skipped files, to append to "unknown pass type" errors.
    std::string plugin_problems_note() const;

private:
    std::vector<std::string> run_trusted_;  // canonical search-path folders
};

}  // namespace pathlet
