// Variant 2's artefact on the built-in study phantom: the darkening of pixels whose front
// fragment is faded, against the unlit OIT colour, for the faithful graph and the better one,
// with the node statistics of the frame. Timing comparisons: `pathlet bench variant1_lineao,
// variant2_oit,variant2_oit_ao --size 1280x720,1920x1080`.
//   build/bin/bench_oit [WxH] [time]
#include "oit_metric.hpp"

#include "phantom/phantom.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

using namespace pathlet;

int main(int argc, char** argv) {
    glm::ivec2 size{1280, 720};
    if (argc > 1) std::sscanf(argv[1], "%dx%d", &size.x, &size.y);
    double t = argc > 2 ? std::atof(argv[2]) : 9.0;
    Scene scene = phantom::load_or_make_phantom("study");
    std::string dir = (std::filesystem::temp_directory_path() / "pathlet_bench_oit").string();
    std::filesystem::create_directories(dir);
    std::printf("variant 2 artefact, study phantom (%zu lines), %dx%d, t = %.2f s\n", scene.lines.line_count(), size.x,
                size.y, t);
    std::printf("  %-18s %12s %14s %16s %10s %12s %10s\n", "graph", "darkening", "faded pixels", "(opaque front)",
                "nodes", "peak/pixel", "overflows");
    for (const char* name : {"variant2_oit", "variant2_oit_ao", "variant2_oit_vao"}) {
        oit_test::MetricGraph g = oit_test::metric_graph(std::string(PATHLET_SOURCE_DIR) + "/graphs/" + name + ".json", dir);
        RenderOptions opt;
        opt.graph_path = g.path;
        opt.size = size;
        opt.time.start = t;
        Frame f = render_frame(test_runtime(), scene, opt, {g.final_name, g.unlit_name, g.front_alpha_name});
        oit_test::Artefact a = oit_test::measure_artefact(f, g);
        std::printf("  %-18s %9.1f/255 %14zu %12.1f/255 %10.0f %12.0f %10.0f\n", name, 255.0 * a.darkening, a.pixels,
                    255.0 * a.opaque_darkening, f.stats["nodes"], f.stats["peak_nodes_per_pixel"],
                    f.stats["overflow_events_total"]);
    }
    std::filesystem::remove_all(dir);
    return 0;
}
