// pathlet graph FILE --dot/--plan: the compiled plan (order, culling, lifetimes, pooling).
#include "args.hpp"
#include "commands.hpp"
#include "graph/graph_model.hpp"
#include "renderer.hpp"
#include "runtime.hpp"

#include <pathlet/gl.hpp>
#include "util/atomic_file.hpp"

#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("graph", "Compiles a graph for an output size and shows the result: the execution order, culled\n"
                    "passes and why, resource lifetimes, pooling and memory before and after pooling.");
    a.positional("GRAPH", "graph file (or the name of a shipped graph, e.g. variant1_lineao)")
        .flag("plan", "print the plan as text (the default)")
        .flag("json", "print the plan as JSON")
        .flag("expanded", "print the graph as one JSON document: the graphs it extends merged in (the document "
                          "error pointers refer to)")
        .option("dot", "FILE", "", "write Graphviz DOT to FILE ('-' for stdout); render with: dot -Tsvg FILE -o g.svg")
        .option("size", "WxH", "1280x720", "output size the plan is computed for")
        .multi("set", "NAME=VALUE", "override a variable or pass parameter")
        .multi("plugin-dir", "DIR", "also load plugins from DIR")
        .example("pathlet graph variant1_lineao --plan", "order, lifetimes and memory of the LineAO graph")
        .example("pathlet graph graphs/isl.json --dot isl.dot", "graph picture as DOT")
        .example("pathlet graph plugins/example_fade/speed_fade_v1.json --expanded", "a graph that extends variant 1, merged");
    if (!a.parse(argv)) return 0;
    glm::ivec2 size;
    try {
        size = parse_size(a.get("size"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    std::string path = resolve_graph_path(a.pos("GRAPH"));
    try {
        if (a.has("expanded")) {  // what the file stands for, before --set and validation
            std::printf("%s\n", expanded_graph_json(path).dump(2).c_str());
            return 0;
        }
        GraphFile g = rt.load_graph(path, a.all("set"));
        CompiledGraph cg = compile_graph(g, rt.registry, size);
        if (a.has("dot")) {
            std::string dot = graph_to_dot(cg, g);
            if (a.get("dot") == "-")
                std::fputs(dot.c_str(), stdout);
            else
                write_file_atomic(a.get("dot"), dot);
        }
        if (a.has("json"))
            std::printf("%s\n", plan_to_json(cg).dump(2).c_str());
        else if (a.has("plan") || !a.has("dot"))
            std::fputs(plan_to_text(cg).c_str(), stdout);
        return 0;
    } catch (const GraphError& e) {
        for (const auto& d : e.diagnostics) std::fprintf(stderr, "%s\n", d.str().c_str());
        std::fprintf(stderr, "%s", rt.plugin_problems_note().c_str());
        return 1;
    }
}

PATHLET_COMMAND("graph", "compile a graph and show its plan (--plan) or Graphviz picture (--dot)", run);

}  // namespace
}  // namespace pathlet::cli
