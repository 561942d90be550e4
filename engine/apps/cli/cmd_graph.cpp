// pathlet graph FILE --dot/--plan: the compiled plan (order, culling, lifetimes, pooling).
#include "commands.hpp"
#include "common_options.hpp"
#include "graph_errors.hpp"
#include "graph/graph_model.hpp"
#include "renderer.hpp"
#include "runtime.hpp"

#include <pathlet/gl.hpp>
#include <pathlet/gpu_scene.hpp>
#include <pathlet/line_chunks.hpp>
#include <pathlet/lines.hpp>
#include "util/atomic_file.hpp"

#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <cmath>
#include <cstdio>

namespace pathlet::cli {
namespace {

// The memory a data set adds besides the graph's resources: the line points and their level of
// detail on the GPU, the chunks the line kit culls by (CPU and GPU), and what each culling line
// pass keeps on the GPU. Per unit without data, measured with it.
std::string scene_memory_text(const SceneOptions& data) {
    constexpr double kMiB = 1024.0 * 1024.0;
    const size_t chunk_bytes = sizeof(LineChunks::Chunk);
    char buf[768];
    if (!data.given()) {
        std::snprintf(buf, sizeof buf,
                      "data (not in the totals above): line points %zu B each (GPU, with the level of detail); line "
                      "chunks %zu B per %u segments (CPU, for culling) + %zu B (GPU); each culling line pass %zu B per "
                      "chunk + %zu B per segment (GPU); --phantom or --data gives the sizes for a data set\n",
                      GpuScene::point_memory(1, 0, GpuScene::default_point_layout()).total(), chunk_bytes,
                      LineChunks::kSegments, GpuScene::kGpuChunkBytes,
                      lines::culling_bytes(1, 0), lines::culling_bytes(0, 1));
        return buf;
    }
    const Scene scene = data.load(true);
    LineChunks chunks;
    chunks.build(scene.lines);
    const size_t segments = chunks.segments();
    std::snprintf(buf, sizeof buf,
                  "data %s (not in the totals above): %zu lines, %zu points: line points %.2f MiB (GPU), %zu line "
                  "chunks %.2f MiB (CPU, for culling) + %.2f MiB (GPU); each culling line pass %.2f MiB (GPU)\n",
                  scene.source.c_str(), scene.lines.line_count(), scene.lines.point_count(),
                  double(GpuScene::point_memory(scene.lines.point_count(), 0, GpuScene::default_point_layout()).total()) / kMiB,
                  chunks.chunks().size(),
                  double(chunks.bytes()) / kMiB, double(chunks.chunks().size() * GpuScene::kGpuChunkBytes) / kMiB,
                  double(lines::culling_bytes(chunks.chunks().size(), segments)) / kMiB);
    return buf;
}

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

// Every pass's parameters as this graph runs them: value, type, default, range, where a hook's
// parameter is declared, and the doc (a hook's @param lines included).
std::string params_text(const CompiledGraph& cg) {
    std::string s;
    for (const auto& p : cg.passes) {
        s += p.name + " [" + p.type->type + "]\n";
        for (const auto& h : p.hooks) s += "  (hook " + h.param + ": " + h.file + ")\n";
        for (const ParamDecl& d : p.type->params) {
            s += "  " + d.name + " = " + (p.params.contains(d.name) ? p.params[d.name].dump() : d.def.dump()) + "  (" +
                 to_string(d.type) + ", default " + d.def.dump();
            if ((d.type == ParamType::Int || d.type == ParamType::Float) && (std::isfinite(d.min) || std::isfinite(d.max)))
                s += ", range [" + number(d.min) + ", " + number(d.max) + "]";
            if (d.type == ParamType::Enum) s += ", one of " + text::join(d.choices);
            if (d.pixels) s += ", pixels";
            if (!d.origin.empty()) s += ", from " + d.origin;
            s += ")\n      " + d.doc + "\n";
        }
    }
    return s;
}

int run(const std::vector<std::string>& argv) {
    Args a("graph", "Compiles a graph for an output size and shows the result: the execution order, culled\n"
                    "passes and why, resource lifetimes, pooling and memory before and after pooling.");
    std::string graph, dot;
    bool plan = false, as_json = false, expanded = false, params = false;
    glm::ivec2 size{1280, 720};
    std::vector<std::string> sets;
    PluginOptions plugins;
    SceneOptions data;
    a.positional("GRAPH", graph, "graph file (or the name of a shipped graph, e.g. variant1_lineao)")
        .flag("plan", plan, "print the plan as text (the default)")
        .flag("json", as_json, "print the plan as JSON")
        .flag("params", params, "print every pass's parameters as this graph runs them: value, type, default, range, "
                                "doc; a hook file's @param parameters with the file and line that declare them")
        .flag("expanded", expanded, "print the graph as one JSON document: the graphs it extends merged in (the document "
                                    "error pointers refer to)")
        .option("dot", dot, "FILE", "write Graphviz DOT to FILE ('-' for stdout); render with: dot -Tsvg FILE -o g.svg");
    declare_size(a, size, "output size the plan is computed for");
    declare_sets(a, sets);
    plugins.declare(a);
    data.declare(a);
    a.example("pathlet graph variant1_lineao --plan", "order, lifetimes and memory of the LineAO graph")
        .example("pathlet graph variant1_lineao --plan --phantom study", "... and the memory of the study phantom's lines")
        .example("pathlet graph graphs/isl.json --dot isl.dot", "graph picture as DOT")
        .example("pathlet graph plugins/example_fade/speed_fade_v1.json --params", "parameters, with the hook's own")
        .example("pathlet graph plugins/example_fade/speed_fade_v1.json --expanded", "a graph that extends variant 1, merged");
    if (!a.parse(argv)) return 0;
    Runtime rt;
    plugins.load(rt);
    sets = rt.user_sets(sets);
    std::string path = resolve_graph_path(graph);
    try {
        if (expanded) {  // what the file stands for, before --set and validation
            std::printf("%s\n", expanded_graph_json(path).dump(2).c_str());
            return 0;
        }
        GraphFile g = rt.load_graph(path, sets);
        print_graph_notes(g);
        CompiledGraph cg = compile_graph(g, rt.registry, size);
        if (!dot.empty()) {
            const std::string text = graph_to_dot(cg, g);
            if (dot == "-")
                std::fputs(text.c_str(), stdout);
            else
                write_file_atomic(dot, text);
        }
        if (params) std::fputs(params_text(cg).c_str(), stdout);
        if (as_json)
            std::printf("%s\n", plan_to_json(cg).dump(2).c_str());
        else if (plan || (dot.empty() && !params)) {
            std::fputs(plan_to_text(cg).c_str(), stdout);
            std::fputs(scene_memory_text(data).c_str(), stdout);
        }
        return 0;
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
}

PATHLET_COMMAND("graph", "compile a graph and show its plan (--plan) or Graphviz picture (--dot)", run);

}  // namespace
}  // namespace pathlet::cli
