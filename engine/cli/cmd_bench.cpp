// pathlet bench GRAPH...: the same data, camera, times and sizes through several graphs;
// prints each graph's per-pass table (like the study's Table 3) and a side-by-side summary.
#include "args.hpp"
#include "util/output_check.hpp"
#include "commands.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "util/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace pathlet::cli {
namespace {

// --set for one graph only: "GRAPH:NAME=VALUE" where GRAPH is a graph as listed (its name or
// file) or its 1-based position in the list (so one graph can run twice, set differently).
// Plain "NAME=VALUE" goes to every graph. Returns the overrides of graph `index` (0-based).
std::vector<std::string> sets_for(const std::vector<std::string>& all, const std::vector<std::string>& graphs, size_t index) {
    std::vector<std::string> out;
    for (const auto& s : all) {
        const size_t colon = s.find(':'), eq = s.find('=');
        if (colon == std::string::npos || (eq != std::string::npos && eq < colon)) {
            out.push_back(s);  // no qualifier (a ':' inside the value does not count)
            continue;
        }
        const std::string q = s.substr(0, colon);
        bool known = false;
        for (size_t i = 0; i < graphs.size(); ++i) {
            bool match = q == graphs[i] || q == std::to_string(i + 1);
            known |= match;
            if (match && i == index) out.push_back(s.substr(colon + 1));
        }
        if (!known) {
            std::string list;
            for (size_t i = 0; i < graphs.size(); ++i) list += (i ? ", " : "") + std::to_string(i + 1) + " = " + graphs[i];
            throw UsageError("--set '" + s + "': '" + q + "' is none of the graphs (" + list + ")");
        }
    }
    return out;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string tok;
    while (std::getline(in, tok, sep))
        if (!tok.empty()) out.push_back(tok);
    return out;
}

int run(const std::vector<std::string>& argv) {
    Args a("bench",
           "Times graphs over the same data, camera, times and output sizes. For every graph and size it\n"
           "prints the per-pass table (median, p5, p95 in ms, share of the frame) and ends with a summary\n"
           "of frame times and frames per second. Nothing is written unless --report is given.");
    a.positional("GRAPHS", "comma-separated graph files or shipped graph names (e.g. variant1_lineao,isl)")
        .option("size", "WxH[,WxH...]", "1280x720", "output sizes to measure")
        .option("time", "T|A:B:STEP", "9", "animation time(s) rendered")
        .option("frames", "N", "10", "measured frames per time (after warm-up)")
        .option("warmup", "N", "3", "frames before timing starts")
        .multi("set", "[GRAPH:]NAME=VALUE",
               "override a variable or pass parameter: in every graph, or with GRAPH: (a graph as listed, or its "
               "position 1, 2, ...) in that one only; unknown names are errors")
        .option("timing", "auto|gpu|finish", "auto", "timing backend (auto: finish on llvmpipe, timestamps on a GPU)")
        .option("camera", "FILE", "", "camera path JSON (default: frame the data)")
        .option("report", "PREFIX", "", "write PREFIX.csv and PREFIX.json with every pass of every run")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
    a.example("pathlet bench variant1_lineao,isl --size 1280x720,1920x1080",
              "the study's comparison on the built-in phantom with a 1 s pathlet window")
        .example("pathlet bench variant1_lineao --set window=0", "every line drawn (no time window)")
        .example("pathlet bench variant3_geomfade,variant3_geomfade --set 2:fade_measure=arc_length",
                 "one graph twice, side by side: taper measured in time (1) and in arc length (2)");
    if (!a.parse(argv)) return 0;

    std::vector<glm::ivec2> sizes;
    RenderOptions base;
    try {
        for (const auto& s : split(a.get("size"), ',')) sizes.push_back(parse_size(s));
        base.time = parse_time_range(a.get("time"));
        base.timing = parse_timing_backend(a.get("timing"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    base.repeat = int(a.integer("frames"));
    base.warmup = int(a.integer("warmup"));
    if (base.repeat < 1 || base.warmup < 0) throw UsageError("--frames must be >= 1 and --warmup >= 0");
    base.sets = a.all("set");
    base.camera_path = a.get("camera");
    base.write_images = false;
    base.quiet = true;

    if (a.has("report")) check_output_file(a.get("report") + ".csv", "the report (--report)");  // before the run

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    Scene scene = load_scene(a, false);
    rt.ensure_gl(false);

    struct Row {
        std::string graph;
        glm::ivec2 size;
        Profiler::Stats frame;
    };
    std::vector<Row> rows;
    std::string csv;
    json runs = json::array();
    const std::vector<std::string> graphs = split(a.pos("GRAPHS"), ',');
    for (size_t gi = 0; gi < graphs.size(); ++gi) sets_for(base.sets, graphs, gi);  // bad qualifiers: before any work
    for (size_t gi = 0; gi < graphs.size(); ++gi) {
        const std::vector<std::string> own = sets_for(base.sets, graphs, gi);
        std::string gname = graphs[gi];
        for (const auto& s : own)  // label rows with the overrides only this graph gets
            if (std::find(base.sets.begin(), base.sets.end(), s) == base.sets.end()) gname += " [" + s + "]";
        for (glm::ivec2 size : sizes) {
            RenderOptions opt = base;
            opt.sets = own;
            opt.graph_path = resolve_graph_path(graphs[gi]);
            opt.size = size;
            RenderResult r;
            try {
                r = render(rt, scene, opt);
            } catch (const GraphError& e) {
                for (const auto& d : e.diagnostics) std::fprintf(stderr, "%s\n", d.str().c_str());
                std::fprintf(stderr, "%s", rt.plugin_problems_note().c_str());
                return 1;
            }
            std::string title = gname + " — " + std::to_string(size.x) + "x" + std::to_string(size.y) + ", " +
                                std::to_string(scene.lines.line_count()) + " lines";
            std::printf("%s\n", r.profiler.table(title).c_str());
            rows.push_back({gname, size, r.profiler.frame_ms()});
            json meta = {{"graph", opt.graph_path}, {"size", {size.x, size.y}}, {"renderer", rt.gl->renderer()},
                         {"data", scene.source}, {"sets", own}};
            runs.push_back(r.profiler.to_json(meta));
            std::string c = r.profiler.csv();
            // Prefix every CSV row with graph and size so runs can be concatenated.
            std::stringstream in(c);
            std::string line;
            bool header = true;
            while (std::getline(in, line)) {
                if (header) {
                    if (csv.empty()) csv += "graph,size," + line + "\n";
                    header = false;
                    continue;
                }
                csv += gname + "," + std::to_string(size.x) + "x" + std::to_string(size.y) + "," + line + "\n";
            }
        }
    }
    std::printf("summary (%s; %s)\n", rt.gl->renderer().c_str(), scene.source.c_str());
    std::printf("  %-28s %-11s %10s %10s %10s %8s\n", "graph", "size", "median ms", "p5 ms", "p95 ms", "fps");
    for (const auto& r : rows)
        std::printf("  %-28s %-11s %10.2f %10.2f %10.2f %8.1f\n", r.graph.c_str(),
                    (std::to_string(r.size.x) + "x" + std::to_string(r.size.y)).c_str(), r.frame.median, r.frame.p5,
                    r.frame.p95, r.frame.median > 0 ? 1000.0 / r.frame.median : 0.0);
    if (a.has("report")) {
        write_file_atomic(a.get("report") + ".csv", csv);
        write_file_atomic(a.get("report") + ".json", runs.dump(2));
        std::fprintf(stderr, "wrote %s.csv and %s.json\n", a.get("report").c_str(), a.get("report").c_str());
    }
    return 0;
}

PATHLET_COMMAND("bench", "time several graphs on the same data and sizes; per-pass tables and a summary", run);

}  // namespace
}  // namespace pathlet::cli
