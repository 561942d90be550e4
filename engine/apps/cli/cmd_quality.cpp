// pathlet quality [GRAPH]: measures of AO quality at a fixed camera (issues 13 and 25):
// temporal flicker against the change of the geometry and of the ray-traced AO, and the error
// of the AO against a ray-traced AO of the same frame (Embree, tubes of the visible pathlets).
// The measuring is quality/measure.cpp (shared with the Python module); this is the command.
#include "commands.hpp"
#include "common_options.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"

#include "measure.hpp"

#include <algorithm>
#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("quality",
           "Measures AO quality (LineAO, volume AO, or per-fragment AO under OIT) at a fixed camera over a\n"
           "time range: temporal flicker (mean frame-to-frame change of AO where the same line is seen at\n"
           "the same depth) against the change of the geometry and against the change of the ray-traced AO,\n"
           "and the error (MAE, correlation) against a CPU ray-traced AO (Embree, tubes of the visible\n"
           "pathlets, cosine-weighted rays, the pixel's own line left out) of the last frame, with an error image.");
    std::string graph = "variant1_lineao";
    PluginOptions plugins;
    SceneOptions data;
    quality::QualityOptions q;
    q.size = {320, 180};
    q.work_dir = "out/quality";
    a.positional("GRAPH", graph, "graph file or shipped graph name (default: variant1_lineao)", false)
        .option("time", q.time, "A:B:STEP",
                "animation times (frames at A, A+STEP, ... <= B); default: 11 frames 0.04 s apart from the middle of "
                "the data's time span (the study phantom's 9:9.4:0.04)");
    declare_size(a, q.size, "output size in pixels");
    bool images = false;
    a.option("rays", q.rays, "N", "ray-traced AO: rays per pixel")
        .option("flicker-rays", q.flicker_rays, "N",
                "ray-traced AO of every frame, for the flicker against the reference's own change: rays per pixel "
                "(0: not measured)")
        .option("max-distance", q.max_distance, "WIDTHS", "ray-traced AO: ray length in line widths")
        .flag("include-own-line", q.own_line, "ray-traced AO: a pixel's own line occludes it too (issue 13's reference)")
        .option("depth-tolerance", q.depth_tolerance, "D",
                "flicker: largest change of linear depth that counts as unchanged")
        .option("out", q.work_dir, "DIR", "folder for the per-pixel error image")
        .flag("images", images,
              "also write the last frame's AO and the ray-traced AO as grey images (NAME_ao.png, NAME_reference.png)");
    declare_sets(a, q.sets);
    plugins.declare(a);
    data.declare(a);
    if (!a.parse(argv)) return 0;
    q.graph_path = resolve_graph_path(graph);
    try {
        quality::check_quality_options(q);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }

    Runtime rt;
    plugins.load(rt);
    q.sets = rt.user_sets(q.sets);
    Scene scene = data.load(true);
    const quality::QualityResult r = quality::measure_quality(rt, scene, q);
    if (!r.not_measured.empty()) {
        std::printf("%s: not measured: %s\n", r.graph.c_str(), r.not_measured.c_str());
        return 0;
    }
    const std::string image = q.work_dir + "/" + r.graph + "_error.png";
    ensure_parent_dir(image);
    write_image(image, quality::error_image(r.last, r.error.abs_error));
    if (images) {
        write_image(q.work_dir + "/" + r.graph + "_ao.png", quality::ao_image(r.last, r.last.ao));
        write_image(q.work_dir + "/" + r.graph + "_reference.png", quality::ao_image(r.last, r.reference));
    }

    std::printf("%s: %zu frames %dx%d, t=%.2f..%.2f\n", r.graph.c_str(), r.frames, q.size.x, q.size.y, r.first_time,
                r.last_time);
    std::printf("  flicker: mean |dAO| %.5f over %zu stable pixels; geometry change %.3f of covered pixels\n",
                r.flicker.ao_flicker, r.flicker.stable_pixels, r.flicker.geometry_change);
    if (q.flicker_rays > 0)
        std::printf("  ray-traced AO (%d rays/px) changes by %.5f at those pixels; the AO's change beyond it, mean "
                    "|dAO - dRT|: %.5f\n",
                    q.flicker_rays, r.reference_flicker.reference_change, r.reference_flicker.excess);
    std::printf("  vs ray-traced AO (%d rays/px, reach %.3g = %.0f line widths, %zu tube segments): MAE %.4f, "
                "correlation %.3f over %zu px\n",
                q.rays, r.reach, q.max_distance, r.segments, r.error.mae, r.error.correlation, r.error.pixels);
    std::printf("  error image: %s\n", image.c_str());
    return 0;
}

PATHLET_COMMAND("quality", "AO quality: temporal flicker and error against ray-traced AO", run);

}  // namespace
}  // namespace pathlet::cli
