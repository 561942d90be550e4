// pathlet render [GRAPH]: run a graph over a time range and write images (and a video).
#include "args.hpp"
#include "util/output_check.hpp"
#include "commands.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "util/atomic_file.hpp"
#include "bench/shard.hpp"
#include "progress.hpp"
#include "video_writer.hpp"

#include <memory>

#include <cstdio>
#include <filesystem>

namespace pathlet::cli {
namespace {

void write_reports(const RenderResult& r, const std::string& prefix, const json& meta) {
    namespace fs = std::filesystem;
    if (fs::path(prefix).has_parent_path()) fs::create_directories(fs::path(prefix).parent_path());
    write_file_atomic(prefix + ".csv", r.profiler.csv());
    write_file_atomic(prefix + ".json", r.profiler.to_json(meta).dump(2));
    write_file_atomic(prefix + ".trace.json", r.profiler.chrome_trace().dump());
    std::fprintf(stderr, "timings: %s.csv, %s.json, %s.trace.json (open the trace in https://ui.perfetto.dev)\n",
                 prefix.c_str(), prefix.c_str(), prefix.c_str());
}

int run(const std::vector<std::string>& argv) {
    Args a("render",
           "Renders a graph over a time range to image files (PNG by default, EXR for float outputs) and\n"
           "prints the per-pass timing table. Without arguments it renders the built-in aortic-arch\n"
           "phantom (generated on first use and cached) through the LineAO graph variant1_lineao.");
    a.positional("GRAPH", "graph file, or the name of a shipped graph (default: variant1_lineao)", false)
        .option("time", "T|A:B|A:B:STEP", "", "animation times in seconds (frames at A, A+STEP, ... <= B); default: the data's whole time span in 0.25 s steps")
        .option("size", "WxH", "1280x720", "output size in pixels")
        .option("ssaa", "N", "1",
                "supersampling for offline renders: render N x N larger (LineAO radii, filter widths and the "
                "level of detail scaled with it) and box-filter every frame down to --size (1..8)")
        .option("out", "DIR", "out", "output folder ({out} in the graph's capture patterns)")
        .multi("set", "NAME=VALUE", "override a graph variable or a pass parameter: --set lineao.strength=2")
        .option("camera", "FILE", "", "camera path JSON: {\"keyframes\": [{\"time\", \"eye\", \"target\", \"up\", \"fov\"}]}")
        .option("orbit", "DEG_PER_S", "0", "turntable: rotate the camera about the data at this rate")
        .option("timing", "auto|gpu|finish", "auto",
                "pass timing: GL timestamp queries (gpu), glFinish-bracketed CPU clock (finish; used on llvmpipe)")
        .option("warmup", "N", "2", "frames rendered before timing starts (shader JIT on llvmpipe)")
        .option("report", "PREFIX", "", "also write PREFIX.csv, PREFIX.json and PREFIX.trace.json (Perfetto)")
        .option("video", "FILE.mp4", "", "also encode the frames to a video (needs ffmpeg on PATH)")
        .option("fps", "N", "25", "video frame rate")
        .option("shard", "I/N", "", "render only frames k with k % N == I (0-based; Slurm array part), same file names")
        .flag("no-images", "do not write image files (timing runs)")
        .flag("quiet", "no progress bar or notes")
        .multi("plugin-dir", "DIR", "also load plugins from DIR");
    add_scene_options(a);
    a.example("pathlet render", "the phantom through variant1_lineao.json into out/, with a timing table")
        .example("pathlet render isl --time 9 --size 1920x1080", "one frame of illuminated streamlines")
        .example("pathlet render --time 9 --size 1920x1080 --ssaa 4", "a figure: 4x4 supersampled")
        .example("pathlet render graphs/lineao_debug.json --time 9 --set lineao.samples=58",
                 "every intermediate map of one LineAO frame, with 58 samples")
        .example("pathlet render --data flow.vtp --mesh aorta.glb --time 0:18:0.04 --video flow.mp4",
                 "your own data, 25 fps, as a video");
    if (!a.parse(argv)) return 0;

    RenderOptions opt;
    try {
        opt.graph_path = resolve_graph_path(a.pos("GRAPH").empty() ? "variant1_lineao" : a.pos("GRAPH"));
        opt.size = parse_size(a.get("size"));
        if (a.has("time")) opt.time = parse_time_range(a.get("time"));
        opt.timing = parse_timing_backend(a.get("timing"));
        if (a.has("shard")) {
            Shard sh = parse_shard(a.get("shard"));
            opt.shard_index = sh.index;
            opt.shard_count = sh.count;
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    opt.sets = a.all("set");
    opt.out_dir = a.get("out");
    opt.camera_path = a.get("camera");
    opt.orbit_deg_per_s = a.number("orbit");
    opt.warmup = int(a.integer("warmup"));
    opt.ssaa = int(a.integer("ssaa"));
    if (opt.ssaa < 1 || opt.ssaa > 8) throw UsageError("--ssaa must be 1..8 (got " + a.get("ssaa") + ")");
    if (opt.size.x * opt.ssaa > 16384 || opt.size.y * opt.ssaa > 16384)
        throw UsageError("--size x --ssaa exceeds 16384 pixels on a side; lower one of them");
    if (opt.warmup < 0) throw UsageError("--warmup must be >= 0");
    std::string video_path = a.get("video");
    if (opt.shard_count > 1 && !video_path.empty())
        throw UsageError("--video with --shard: each shard has only some frames; encode the joined frames (scripts/slurm/)");
    const double fps = a.number("fps");
    opt.write_images = !a.has("no-images");
    opt.quiet = a.has("quiet");
    if (!video_path.empty() && !VideoWriter::available())
        std::fprintf(stderr, "warning: ffmpeg not found on PATH; --video ignored (images are still written)\n"),
            video_path.clear();

    // Before GL set-up and data loading: every output place must take files.
    if (opt.write_images) check_output_dir(opt.out_dir, "images (--out)");
    if (a.has("report")) check_output_file(a.get("report") + ".csv", "the timing report (--report)");
    if (!video_path.empty()) check_output_file(video_path, "the video (--video)");

    Runtime rt;
    rt.load_plugins(a.all("plugin-dir"));
    Scene scene = load_scene(a, opt.quiet);
    if (!a.has("time"))  // streamlines are drawn whole: one frame, not the same picture over their pseudo-time
        opt.time = scene.lines.timeless ? TimeRange{0, 0, 0.25} : TimeRange{scene.lines.time_min(), scene.lines.time_max(), 0.25};
    try {
        std::unique_ptr<VideoWriter> video;
        if (!video_path.empty()) {
            ensure_parent_dir(video_path);
            video = std::make_unique<VideoWriter>(video_path, opt.size.x, opt.size.y, fps);
            opt.on_image = [&](const Image& img) { video->add_frame(img); };
        }
        std::unique_ptr<Progress> progress;
        opt.on_progress = [&](size_t done, size_t total) {
            if (!progress) progress = std::make_unique<Progress>("frames", total, opt.quiet);
            progress->update(done);
        };
        RenderResult r = render(rt, scene, opt);
        if (video) {
            video->close();
            r.files.push_back(video_path);
        }
        if (progress) progress->finish(std::to_string(r.frames) + " frames");
        std::string title = graph_display_name(parse_graph_file(opt.graph_path)) + " — " +
                            std::to_string(opt.size.x) + "x" + std::to_string(opt.size.y) + ", " +
                            std::to_string(r.frames) + " frames, " + std::to_string(scene.lines.line_count()) +
                            " lines, " + std::to_string(scene.lines.point_count()) + " points";
        std::printf("%s", r.profiler.table(title).c_str());
        if (!r.files.empty())
            std::fprintf(stderr, "wrote %zu file(s), e.g. %s\n", r.files.size(), r.files.back().c_str());
        if (a.has("report")) {
            json meta = {{"graph", opt.graph_path}, {"renderer", rt.gl->renderer()}, {"size", {opt.size.x, opt.size.y}},
                         {"frames", r.frames}, {"data", scene.source}, {"variables", r.compiled.variables}};
            write_reports(r, a.get("report"), meta);
        }
        return 0;
    } catch (const GraphError& e) {
        for (const auto& d : e.diagnostics) std::fprintf(stderr, "%s\n", d.str().c_str());
        std::fprintf(stderr, "%s", rt.plugin_problems_note().c_str());
        return 1;
    }
}

PATHLET_COMMAND("render", "render a graph over a time range to images/video, with a timing table", run);

}  // namespace
}  // namespace pathlet::cli
