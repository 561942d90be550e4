#include "runtime.hpp"

#include <algorithm>
#include <cstdio>

namespace pathlet {

void Runtime::load_plugins(const std::vector<std::string>& extra_dirs) {
    host.load_dirs(PluginHost::search_path(extra_dirs));
}

void Runtime::load_graph_plugins(const GraphFile& g) {
    std::vector<std::string> fresh;
    for (const auto& d : g.plugin_dirs) {
        const auto& seen = registry.searched_dirs();
        if (std::find(seen.begin(), seen.end(), d) == seen.end()) fresh.push_back(d);
    }
    host.load_dirs(fresh);
}

GraphFile Runtime::load_graph(const std::string& path, const std::vector<std::string>& sets) {
    GraphFile g = parse_graph_file(path);
    load_graph_plugins(g);
    std::vector<Diagnostic> diags;
    apply_overrides(g, sets, registry, diags);
    if (!diags.empty()) throw GraphError(diags);
    return g;
}

GlContext& Runtime::ensure_gl(bool quiet) {
    if (!gl) {
        gl = GlContext::create_headless();
        if (!quiet) std::fprintf(stderr, "%s\n", gl->summary().c_str());
    }
    return *gl;
}

std::string Runtime::plugin_problems_note() const {
    if (host.problems().empty()) return "";
    std::string s = "\nnote: " + std::to_string(host.problems().size()) + " plugin(s) failed to load:";
    for (const auto& p : host.problems()) s += "\n  " + p;
    return s;
}

}  // namespace pathlet
