// pathlet quality [GRAPH]: measures of AO quality at a fixed camera:
// temporal flicker against the change of the geometry and of the ray-traced AO, and the error
// of the AO against a ray-traced AO of the same frame (Embree, tubes of the visible pathlets).
// The measuring is quality/measure.cpp (shared with the Python module); this is the command.
#include "commands.hpp"
#include "graph_errors.hpp"
#include "common_options.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"

#include "bench/experiment.hpp"
#include "bench/run_experiment.hpp"
#include "ao_options.hpp"
#include "measure.hpp"
#include "reference.hpp"
#include "transparency.hpp"

#include <algorithm>
#include <type_traits>
#include <cmath>
#include <cstdio>

namespace pathlet::cli {
namespace {

// --transparency --experiment: one row per run of the experiment (data set, graph, sweep value).
int run_experiment_table(Runtime& rt, const std::string& file, quality::TransparencyOptions t, bool time_given,
                         bool size_given, const SceneOptions& data) {
    const bench::Experiment e = bench::load_experiment(file);
    bench::graph_info(e, file);  // every graph exists, before any work
    if (!time_given) t.time = e.time.empty() ? std::nullopt : std::optional(parse_time_range(e.time));
    if (!size_given && !e.sizes.empty()) t.size = parse_size(e.sizes.front());
    quality::check_transparency_options(t);
    const size_t frames = t.time ? t.time->times().size() : 11;  // none: default_quality_time's 11
    std::printf("%s: %zu frames at %dx%d per run, focus: the fastest %.0f %% of segments\n", e.name.c_str(),
                frames * size_t(std::max(t.repeat, 1)), t.size.x, t.size.y, 100.0 * t.focus_share);
    std::printf("%-28s %8s %8s %8s %8s %9s %8s %8s %8s\n", "run", "focus", "unocc", "ink", "context", "dalpha", "p95",
                "overflow", "coverage");
    size_t loaded = SIZE_MAX;
    Scene scene;
    for (const bench::Run& run : bench::plan_runs(e)) {
        if (run.size != e.sizes.front()) continue;  // the measures at one size
        if (data.given() && run.data != 0) continue;  // --data/--phantom replace the file's data sets
        if (run.data != loaded) {
            scene = e.data.empty() || data.given() ? data.load(true) : bench::load_data_set(e.data[run.data]);
            loaded = run.data;
        }
        quality::TransparencyOptions o = t;
        o.graph_path = resolve_graph_path(e.graphs[run.graph].graph);
        o.sets = e.sets;
        o.sets.insert(o.sets.end(), e.graphs[run.graph].sets.begin(), e.graphs[run.graph].sets.end());
        if (!e.sweep.param.empty()) o.sets.push_back(e.sweep.param + "=" + run.sweep_value);
        const quality::TransparencyResult r = quality::measure_transparency(rt, scene, o);
        if (!r.not_measured.empty()) {
            std::printf("%-28s not measured: %s\n", run.label.c_str(), r.not_measured.c_str());
            continue;
        }
        std::printf("%-28s %8.4f %8.4f %8.4f %8.4f %9.5f %8.5f %8llu %8.4f\n", run.label.c_str(), r.focus_visibility,
                    r.focus_unoccluded, r.focus_ink_share, r.context_coverage, r.alpha_change_mean, r.alpha_change_p95,
                    (unsigned long long)r.overflow, r.pixel_coverage);
        std::fflush(stdout);
    }
    return 0;
}

// --reference: fidelity of GRAPH against REFGRAPH.
int run_reference(const quality::QualityOptions& q, const std::string& reference, int ssaa, bool out_given,
                  bool transparency, const std::string& experiment, bool allow_empty, double ppd, PluginOptions& plugins,
                  SceneOptions& data) {
    if (transparency || !experiment.empty()) throw UsageError("--reference measures fidelity; not with --transparency or --experiment");
    if (q.time && q.time->times().empty()) throw UsageError("--time gives no frame");
    if (!(ppd > 0.0) || !std::isfinite(ppd)) throw UsageError("--ppd must be a positive number of pixels per degree");
    if (ssaa < 1 || ssaa > 8) throw UsageError("--ssaa-reference must be 1..8 (got " + std::to_string(ssaa) + ")");
    quality::ReferenceOptions o;
    o.ppd = ppd;
    o.reference_ssaa = ssaa;
    o.graph_path = q.graph_path;
    o.reference_path = reference;
    o.size = q.size;
    o.time = q.time;
    if (out_given) o.out_dir = q.work_dir;
    Runtime rt;
    plugins.load(rt);
    o.sets = rt.user_sets(q.sets);
    const Scene scene = data.load(true);
    if (q.time) check_time_in_data(*q.time, shown(*q.time), scene, allow_empty);
    quality::ReferenceResult r;
    try {
        r = quality::measure_against_reference(rt, scene, o);
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
    const quality::ImageMetrics& m = r.metrics;
    std::printf("%s vs %s: %zu frames %dx%d, t=%.2f..%.2f, %zu covered pixels (%.0f a frame)\n", r.graph.c_str(),
                r.reference.c_str(), r.frames, o.size.x, o.size.y, r.first_time, r.last_time, m.pixels,
                double(m.pixels) / double(std::max<size_t>(r.frames, 1)));
    if (!m.ssim_measured()) {  // nothing to measure: no score, and not a success
        std::printf("ssim n/a (no %dx%d window lies inside a %dx%d picture with a covered centre)\n",
                    quality::kSsimWindow, quality::kSsimWindow, o.size.x, o.size.y);
        std::fprintf(stderr, "error: nothing to measure: %zu covered pixels, no SSIM window\n", m.pixels);
        return 2;
    }
    std::printf("ssim %.5f\n", m.ssim);
    std::printf("psnr %.2f\n", m.psnr);
    std::printf("rmse %.5f\n", m.rmse);
    std::printf("share over 8/255 %.4f %%\n", 100.0 * m.share_over);
    std::printf("flip %.5f (mean LDR-FLIP over the covered pixels; all pixels %.5f; %.1f pixels per degree)\n", m.flip,
                m.flip_all, o.ppd);
    std::printf("rms %.2f levels of 255, speckles %.4f %% (the reference's %.4f %%; ../shared/tools/aa_metric.py's figures)\n",
                r.aa.rms, 100.0 * r.aa.speckle, 100.0 * r.reference_aa.speckle);
    if (const std::string note = quality::incomplete_frames_note(r); !note.empty()) std::printf("note: %s\n", note.c_str());
    if (r.flicker)
        std::printf("flicker vs reference %.5f (own change %.5f, the reference's %.5f)\n", r.flicker->excess,
                    r.flicker->test_change, r.flicker->reference_change);
    else
        std::printf("flicker vs reference n/a (one frame)\n");
    for (const std::string& f : r.images) std::printf("wrote %s\n", f.c_str());
    return 0;
}

// The option's spelling on the command line: flicker_rays -> flicker-rays.
std::string option_name(const quality::AoOption& o) {
    std::string name = o.name;
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}

int print_transparency(const quality::TransparencyResult& r, const quality::TransparencyOptions& t) {
    if (!r.not_measured.empty()) {
        std::printf("%s: not measured: %s\n", r.graph.c_str(), r.not_measured.c_str());
        return 0;
    }
    std::printf("%s: %zu frames %dx%d, t=%.2f..%.2f, focus: the fastest %.0f %% of segments (speed >= %.4g)\n",
                r.graph.c_str(), r.frames, t.size.x, t.size.y, r.first_time, r.last_time, 100.0 * t.focus_share,
                r.focus_speed);
    std::printf("focus visibility %.4f unoccluded %.4f\n", r.focus_visibility, r.focus_unoccluded);
    std::printf("focus ink share %.4f\n", r.focus_ink_share);
    std::printf("context coverage %.4f\n", r.context_coverage);
    std::printf("alpha change mean %.5f p95 %.5f\n", r.alpha_change_mean, r.alpha_change_p95);
    std::printf("overflow %llu\n", (unsigned long long)r.overflow);
    std::printf("pixel coverage %.4f\n", r.pixel_coverage);
    return 0;
}

// The error image (and with --images the AO and the reference) written, the figures printed.
int write_and_print_ao(const quality::QualityResult& r, const quality::QualityOptions& q, bool images) {
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

int run(const std::vector<std::string>& argv) {
    Args a("quality",
           "Measures AO quality (LineAO, volume AO, or per-fragment AO under OIT) at a fixed camera over a\n"
           "time range: temporal flicker (mean frame-to-frame change of AO where the same line is seen at\n"
           "the same depth) against the change of the geometry and against the change of the ray-traced AO,\n"
           "and the error (MAE, correlation) against a CPU ray-traced AO (Embree, tubes of the visible\n"
           "pathlets, cosine-weighted rays, the pixel's own line left out) of the last frame, with an error image.\n"
           "With --transparency, what an OIT graph's transparency shows instead, on the fragments of its lists:\n"
           "focus visibility (ink per footprint of the fastest segments, and their unoccluded share), focus ink\n"
           "share, context coverage, the change of each segment's opacity between frames and list overflow.");
    std::string graph;  // "": the data's default graph
    PluginOptions plugins;
    SceneOptions data;
    quality::QualityOptions q;
    q.size = {320, 180};
    q.work_dir = "out/quality";
    a.positional("GRAPH", graph, "graph file or shipped graph name (default: variant1_lineao; tracts_lineao for tracts, said on stderr)", false)
        .option("time", q.time, "A:B:STEP",
                "animation times (frames at A, A+STEP, ... <= B); default: 11 frames 0.04 s apart from the middle of "
                "the data's time span (the study phantom's 9:9.4:0.04)");
    declare_size(a, q.size, "output size in pixels");
    bool images = false, transparency = false;
    quality::TransparencyOptions t;
    std::string experiment, reference;
    double ppd = quality::kFlipPpd;
    int ssaa_reference = 1;
    for (const quality::AoOption& o : quality::ao_options()) {
        const std::string name = option_name(o);
        std::visit(
            [&](auto field) {
                if constexpr (std::is_same_v<decltype(field), bool quality::QualityOptions::*>) a.flag(name, q.*field, o.doc);
                else a.option(name, q.*field, o.metavar, o.doc);
            },
            o.field);
    }
    a.option("out", q.work_dir, "DIR", "folder for the per-pixel error image")
        .flag("images", images,
              "also write the last frame's AO and the ray-traced AO as grey images (NAME_ao.png, NAME_reference.png)")
        .flag("transparency", transparency, "measure the transparency of an OIT graph instead of its AO")
        .option("focus-share", t.focus_share, "F", "--transparency: the fastest share of the data's segments that is focus")
        .option("visible", t.threshold, "TAU",
                "--transparency: ink per footprint pixel from which a context segment counts as visible")
        .option("repeat", t.repeat, "N", "--transparency: frames per time (N > 1 with one time: a frozen view)")
        .option("experiment", experiment, "FILE",
                "--transparency: every graph (and sweep value) of an experiment file on its data sets, one table "
                "row each; its time and first size unless --time/--size are given")
        .option("reference", reference, "REFGRAPH",
                "fidelity instead: GRAPH and REFGRAPH rendered over the same times, size and camera (--set for "
                "both), compared over the pixels either covers: windowed SSIM (Wang et al. 2004, 11x11 Gaussian "
                "on luminance), PSNR, RMSE, the share of pixels more than 8/255 apart, LDR-FLIP (Andersson et al. "
                "2020) and the flicker beyond the reference's own; --out DIR gets the difference and FLIP images")
        .option("ssaa-reference", ssaa_reference, "N",
                "fidelity of the edges: the reference (REFGRAPH, or GRAPH itself without --reference) rendered with "
                "N x N samples a pixel (render --ssaa N, its variable aa off) and box-filtered; adds "
                "../shared/tools/aa_metric.py's rms and speckles")
        .option("ppd", ppd, "PPD",
                "--reference: FLIP's observer in pixels per degree (default 67: 0.7 m from a 0.7 m wide monitor "
                "of 3840 pixels)")
        .example("pathlet quality variant2_exact --reference variant2_depth_peel --set window=0 --size 1280x720",
                 "the exact reference against depth peeling")
        .example("pathlet quality variant1_lineao --ssaa-reference 4 --size 1280x720 --time 9:9.4:0.04",
                 "edges against a 4x4 supersampled render of the same graph, still and in motion")
        .example("pathlet quality variant4_opacity --transparency --size 1280x720", "what the optimized opacity shows")
        .example("pathlet quality --transparency --experiment graphs/experiments/transparency.json",
                 "variant 2, a uniform opacity, a speed transfer function and variant 4 side by side");
    bool allow_empty = false;
    a.flag("allow-empty-frames", allow_empty,
           "measure the --time asked for even where it lies outside the data's time span (empty frames); without "
           "it such a time is an error naming the span");
    declare_sets(a, q.sets);
    plugins.declare(a);
    data.declare(a);
    if (!a.parse(argv)) return 0;
    // An option the chosen measure ignores is an error, not silence.
    std::vector<std::string> ao_only = {"images"};
    for (const quality::AoOption& o : quality::ao_options()) ao_only.push_back(option_name(o));
    const std::vector<std::string> transparency_only = {"focus-share", "visible", "repeat"};
    if (!reference.empty() || ssaa_reference != 1) {
        a.unused_here(ao_only, "with --reference (it compares two graphs' pictures; no AO is ray-traced)");
        a.unused_here(transparency_only, "with --reference (it compares pictures, not the lists' fragments)");
    } else if (transparency) {
        a.unused_here({"ppd", "ssaa-reference"}, "without --reference (FLIP compares two graphs' pictures)");
        a.unused_here(ao_only, "with --transparency (no AO is ray-traced)");
        a.unused_here({"out"}, "with --transparency (it writes no images)");
    } else {
        a.unused_here({"ppd"}, "without --reference (FLIP compares two graphs' pictures)");
        a.unused_here(transparency_only, "without --transparency");
    }
    q.graph_path = resolve_graph_path(graph.empty() ? data.default_graph(false) : graph);
    t.graph_path = q.graph_path;
    t.sets = q.sets;
    t.size = q.size;
    t.time = q.time;
    const bool out_given = std::find(argv.begin(), argv.end(), "--out") != argv.end();
    if (!reference.empty() || ssaa_reference != 1)
        return run_reference(q, reference.empty() ? q.graph_path : resolve_graph_path(reference), ssaa_reference,
                             out_given, transparency, experiment, allow_empty, ppd, plugins, data);
    try {
        if (transparency) quality::check_transparency_options(t);
        else quality::check_quality_options(q);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }

    const bool time_given = std::find(argv.begin(), argv.end(), "--time") != argv.end();
    const bool size_given = std::find(argv.begin(), argv.end(), "--size") != argv.end();
    if (!experiment.empty() && !transparency) throw UsageError("--experiment measures with --transparency only");
    Runtime rt;
    plugins.load(rt);
    q.sets = rt.user_sets(q.sets);
    if (!experiment.empty()) return run_experiment_table(rt, experiment, t, time_given, size_given, data);
    Scene scene = data.load(true);
    if (q.time) check_time_in_data(*q.time, shown(*q.time), scene, allow_empty);
    if (transparency) return print_transparency(quality::measure_transparency(rt, scene, t), t);
    return write_and_print_ao(quality::measure_quality(rt, scene, q), q, images);
}

PATHLET_COMMAND("quality", "AO quality: temporal flicker and error against ray-traced AO", run);

}  // namespace
}  // namespace pathlet::cli
