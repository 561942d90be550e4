#include "runtime.hpp"

#include "plugin_trust.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace pathlet {

namespace fs = std::filesystem;

void Runtime::load_plugins(const std::vector<std::string>& extra_dirs) {
    const std::vector<std::string> dirs = PluginHost::search_path(extra_dirs);
    for (const auto& d : dirs)
        if (std::string c = canonical_dir(d); !c.empty()) run_trusted_.push_back(c);
    host.load_dirs(dirs);
}

namespace {
// Folders of the graph not searched yet (a folder also on --plugin-dir, by any name, is
// loaded once).
std::vector<std::string> fresh_dirs(const GraphFile& g, const PassRegistry& registry) {
    std::vector<std::string> fresh;
    const auto& seen = registry.searched_dirs();
    for (const auto& d : g.plugin_dirs) {
        const std::string c = canonical_dir(d);
        if (std::find(seen.begin(), seen.end(), d) == seen.end() &&
            (c.empty() || std::find(seen.begin(), seen.end(), c) == seen.end()))
            fresh.push_back(c.empty() ? d : c);
    }
    return fresh;
}
}  // namespace

std::vector<GraphFile::UntrustedDir> Runtime::untrusted_plugin_dirs(const GraphFile& g) const {
    std::vector<GraphFile::UntrustedDir> out;
    if (trust_graph_plugins) return out;
    std::vector<std::string> trusted;  // read once, only when a graph names a folder with plugins
    bool read = false;
    for (const auto& d : g.plugin_dirs) {
        const std::string c = canonical_dir(d);
        if (c.empty()) continue;  // no such folder: nothing to load
        PluginHost::FolderScan scan = PluginHost::scan_dir(c);
        if (scan.plugins.empty()) continue;
        if (std::find(run_trusted_.begin(), run_trusted_.end(), c) != run_trusted_.end()) continue;
        if (!read) trusted = read_trusted_dirs(), read = true;
        if (std::find(trusted.begin(), trusted.end(), c) != trusted.end()) continue;
        if (std::none_of(out.begin(), out.end(), [&](const auto& u) { return u.dir == c; }))
            out.push_back({c, std::move(scan.plugins)});
    }
    return out;
}

void Runtime::load_graph_plugins(const GraphFile& g) {
    const auto untrusted = untrusted_plugin_dirs(g);
    if (!untrusted.empty()) {
        std::vector<Diagnostic> diags;
        for (const auto& u : untrusted) {
            std::string files;
            for (const auto& f : u.files) files += "\n    " + f;
            size_t i = 0;  // the entry of plugin_dirs that names it
            while (i + 1 < g.plugin_dirs.size() && canonical_dir(g.plugin_dirs[i]) != u.dir) ++i;
            diags.push_back({g.path, "/plugin_dirs/" + std::to_string(i),
                             "plugin folder " + u.dir +
                                 " is not trusted, so nothing was loaded (a graph file can name any folder, and "
                                 "loading a plugin runs its code). It holds:" + files +
                                 "\n  If you trust it: " + trust_command(u.dir) +
                                 "   (or --trust-graph-plugins for this run only)"});
        }
        throw GraphError(diags);
    }
    host.load_dirs(fresh_dirs(g, registry));
}

void Runtime::load_trusted_graph_plugins(GraphFile& g) {
    g.untrusted_plugin_dirs = untrusted_plugin_dirs(g);
    std::vector<std::string> load;
    for (const auto& d : fresh_dirs(g, registry))
        if (std::none_of(g.untrusted_plugin_dirs.begin(), g.untrusted_plugin_dirs.end(),
                         [&](const auto& u) { return u.dir == d; }))
            load.push_back(d);
    host.load_dirs(load);
}

std::vector<std::string> Runtime::user_sets(std::vector<std::string> sets) {
    std::set<std::string> hooks;  // the hook parameters' names of every loaded type
    for (const PassTypeInfo* t : registry.all())
        for (const ParamDecl& d : t->params)
            if (d.hook) hooks.insert(d.name);
    for (auto& set : sets) {
        const size_t eq = set.find('=');
        if (eq == std::string::npos) continue;
        const std::string lhs = set.substr(0, eq), value = set.substr(eq + 1);
        const size_t dot = lhs.rfind('.');
        // PASS.color_hook=FILE, or a graph variable named as a hook parameter (color_hook=FILE).
        if (!hooks.count(dot == std::string::npos ? lhs : lhs.substr(dot + 1)) || value.empty()) continue;
        const fs::path p = fs::absolute(value).lexically_normal();
        std::error_code ec;
        const bool is_path = value.find('/') != std::string::npos;
        if (!fs::is_regular_file(p, ec)) {
            if (is_path)
                throw std::invalid_argument("--set " + set + ": no hook file '" + value + "' (looked for " + p.string() + ")");
            continue;  // a name on the shader path or next to the graph
        }
        set = lhs + "=" + p.string();
        user_files.insert(p.string());
    }
    return sets;
}

GraphFile Runtime::load_graph(const std::string& path, const std::vector<std::string>& sets, SetsFrom from) {
    GraphFile g = parse_graph_file(path);
    load_graph_plugins(g);
    std::vector<Diagnostic> diags;
    apply_overrides(g, from == SetsFrom::user ? user_sets(sets) : sets, registry, diags, user_files);
    diags.insert(diags.end(), g.hook_problems.begin(), g.hook_problems.end());  // a hook that cannot be used, before any work
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
    std::string s;
    if (!host.problems().empty()) {
        s += "\nnote: " + std::to_string(host.problems().size()) + " plugin(s) failed to load:";
        for (const auto& p : host.problems()) s += "\n  " + p;
    }
    for (const auto& n : host.notes()) s += "\nnote: " + n;
    return s;
}

}  // namespace pathlet
