// pathlet validate FILE...: every problem in each graph at once, with file and JSON pointer.
#include "commands.hpp"
#include "common_options.hpp"
#include "graph_errors.hpp"
#include "graph/graph_model.hpp"
#include "plugin_trust.hpp"
#include "runtime.hpp"

#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("validate", "Checks graph files without rendering: syntax, pass types, parameters, pins, formats,\n"
                       "cycles, writers. Every error is reported at once as FILE:/json/pointer: message.\n"
                       "A graph's plugin folders are loaded only when trusted (see 'pathlet trust --help'); an\n"
                       "untrusted one is never opened, and pass types it may provide are reported as such.");
    std::vector<std::string> files, sets;
    PluginOptions plugins;
    a.rest("GRAPH", files, "graph file(s) to check");
    declare_sets(a, sets);
    plugins.declare(a);
    a.example("pathlet validate graphs/*.json", "check every shipped graph");
    if (!a.parse(argv)) return 0;
    Runtime rt;
    plugins.load(rt);
    sets = rt.user_sets(sets);
    int bad = 0;
    for (const auto& f : files) {
        std::vector<Diagnostic> diags;
        try {
            GraphFile g = parse_graph_file(f);
            rt.load_trusted_graph_plugins(g);  // an untrusted folder is never opened, only named
            for (const auto& u : g.untrusted_plugin_dirs)
                std::fprintf(stderr, "note: %s: plugin folder %s is not trusted; its plugins were not loaded (%s)\n",
                             f.c_str(), u.dir.c_str(), trust_command(u.dir).c_str());
            apply_overrides(g, sets, rt.registry, diags, rt.user_files);
            print_graph_notes(g);
            auto more = validate_graph(g, rt.registry);
            diags.insert(diags.end(), more.begin(), more.end());
        } catch (const GraphError& e) {
            diags.insert(diags.end(), e.diagnostics.begin(), e.diagnostics.end());
        }
        if (diags.empty()) {
            std::printf("%s: ok\n", f.c_str());
        } else {
            ++bad;
            for (const auto& d : diags) std::fprintf(stderr, "%s\n", d.str().c_str());
            std::fprintf(stderr, "%s: %zu error(s)%s\n", f.c_str(), diags.size(), rt.plugin_problems_note().c_str());
        }
    }
    return bad ? 1 : 0;
}

PATHLET_COMMAND("validate", "check graph files; report every error with file and JSON pointer", run);

}  // namespace
}  // namespace pathlet::cli
