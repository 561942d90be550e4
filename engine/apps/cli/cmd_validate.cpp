// pathlet validate FILE...: every problem in each graph at once, with file and JSON pointer,
// and every hook it reaches compiled (FILE:LINE of the hook for each error).
#include "commands.hpp"
#include "common_options.hpp"
#include "gl_context.hpp"
#include "graph_errors.hpp"
#include "graph/graph_model.hpp"
#include "graph/hook_compile.hpp"
#include "plugin_trust.hpp"
#include "runtime.hpp"

#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("validate", "Checks graph files without rendering: syntax, pass types, parameters, pins, formats,\n"
                       "cycles, writers, and compiles every hook file the graph's line passes name (with the GL\n"
                       "driver, headless; a hook's errors name its file and line). Every error is reported at once\n"
                       "as FILE:/json/pointer: message, and counted. A graph's plugin folders are loaded only when\n"
                       "trusted (see 'pathlet trust --help'); an untrusted one is never opened, and pass types it\n"
                       "may provide are reported as such. Exit status: 0 all good, 1 a graph has errors, 2 a GRAPH\n"
                       "names no file and no shipped graph.");
    std::vector<std::string> files, sets;
    bool no_compile = false;
    PluginOptions plugins;
    a.rest("GRAPH", files, "graph file(s) or shipped graph name(s) to check");
    declare_sets(a, sets);
    a.flag("no-compile", no_compile, "do not compile the hooks (no GL context is made)");
    plugins.declare(a);
    a.example("pathlet validate graphs/*.json", "check every shipped graph")
        .example("pathlet validate fade_v1.json --set gbuffer.width_hook=my_fade.glsl", "a graph with another hook");
    if (!a.parse(argv)) return 0;
    Runtime rt;
    plugins.load(rt);
    sets = rt.user_sets(sets);
    int bad = 0, missing = 0;
    bool gl_tried = false;
    std::string no_gl;  // why hooks are not compiled
    for (const auto& arg : files) {
        std::string f;
        try {
            f = find_graph_file(arg);
        } catch (const GraphNotFound& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            ++missing;
            continue;
        }
        std::vector<Diagnostic> diags;
        try {
            GraphFile g = parse_graph_file(f, diags);  // a wrong part is reported, the rest still checked
            rt.load_trusted_graph_plugins(g);  // an untrusted folder is never opened, only named
            for (const auto& u : g.untrusted_plugin_dirs)
                std::fprintf(stderr, "note: %s: plugin folder %s is not trusted; its plugins were not loaded (%s)\n",
                             f.c_str(), u.dir.c_str(), trust_command(u.dir).c_str());
            apply_overrides(g, sets, rt.registry, diags, rt.user_files);
            print_graph_notes(g);
            auto more = validate_graph(g, rt.registry);
            diags.insert(diags.end(), more.begin(), more.end());
            if (!no_compile && !gl_tried) {
                gl_tried = true;
                try {
                    rt.ensure_gl(true);
                } catch (const std::exception& e) {
                    no_gl = e.what();
                }
            }
            if (!no_compile && no_gl.empty()) {
                auto hooks = compile_hooks(g, rt.registry);
                diags.insert(diags.end(), hooks.begin(), hooks.end());
            }
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
    if (!no_gl.empty())
        std::fprintf(stderr, "note: hooks were not compiled (no GL context: %s); the rest was checked\n", no_gl.c_str());
    return missing ? 2 : bad ? 1 : 0;
}

PATHLET_COMMAND("validate", "check graph files and compile their hooks; report every error with file and place", run);

}  // namespace
}  // namespace pathlet::cli
