// pathlet render [GRAPH]: run a graph over a time range and write images (and a video).
#include "bench/shard.hpp"
#include "commands.hpp"
#include "common_options.hpp"
#include "graph_errors.hpp"
#include "output_folders.hpp"
#include "common/progress.hpp"
#include "render_job.hpp"
#include "util/atomic_file.hpp"
#include "util/output_check.hpp"
#include "video_writer.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

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

// SIGINT/SIGTERM while frames render: no new frame starts, the frames rendered so far are
// written, the video is abandoned, nothing half-written stays. A second signal ends the
// program at once (SA_RESETHAND); the next render in that folder removes what it left.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

class StopOnSignals {
public:
    StopOnSignals() {
        g_stop_signal = 0;
        struct sigaction sa = {};
        sa.sa_handler = on_stop_signal;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESETHAND | SA_RESTART;  // writers' pipe and file writes carry on
        sigaction(SIGINT, &sa, &old_int_);
        sigaction(SIGTERM, &sa, &old_term_);
        // Started with a signal ignored (a background job of a script, nohup): it stays ignored.
        if (old_int_.sa_handler == SIG_IGN) sigaction(SIGINT, &old_int_, nullptr);
        if (old_term_.sa_handler == SIG_IGN) sigaction(SIGTERM, &old_term_, nullptr);
    }
    ~StopOnSignals() {
        sigaction(SIGINT, &old_int_, nullptr);
        sigaction(SIGTERM, &old_term_, nullptr);
    }
    StopOnSignals(const StopOnSignals&) = delete;
    StopOnSignals& operator=(const StopOnSignals&) = delete;
    int signal() const { return g_stop_signal; }

private:
    struct sigaction old_int_ = {}, old_term_ = {};
};

// What the command writes besides the frames the graph captures.
struct Extras {
    std::string video_path, report;
    double fps = 25;
    std::vector<std::string> folders;  // the capture folders, marked as the graph's once written
};

// Renders the job's frames over `scene` with progress, writes the video and the report, prints
// the timing table; 128 + the signal when interrupted.
int render_and_report(RenderJob& job, Runtime& rt, const Scene& scene, const Extras& x) {
    const RenderOptions& opt = job.options();
    std::unique_ptr<VideoWriter> video;
    std::function<void(const Image&)> on_image;
    if (!x.video_path.empty()) {
        ensure_parent_dir(x.video_path);
        video = std::make_unique<VideoWriter>(x.video_path, opt.size.x, opt.size.y, x.fps);
        on_image = [&](const Image& img) { video->add_frame(img); };  // a writer thread, in order
    }
    std::unique_ptr<Progress> progress;
    auto on_frames = [&](size_t rendered, size_t written, size_t total) {
        if (!progress) progress = std::make_unique<Progress>("frames", total, opt.quiet);
        // Rendered frames lead; written ones follow as the encoders catch up.
        const bool writes = opt.write_images || video;
        progress->update(rendered, writes ? std::to_string(written) + " written" : "");
    };
    StopOnSignals signals;
    job.set_callbacks(on_image, on_frames, [&] { return signals.signal() != 0; });
    RenderResult r = job.run(scene);
    if (const int sig = signals.signal()) {
        video.reset();  // stops ffmpeg, removes its temp file
        if (progress) progress->finish(std::to_string(r.frames) + " frames", r.profiler.wall_fps());
        std::fprintf(stderr, "interrupted (%s): %zu frame(s) rendered and written%s%s\n",
                     sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "signal", r.frames,
                     r.files.empty() ? "" : (", e.g. " + r.files.back()).c_str(),
                     x.video_path.empty() ? "" : "; the video was not written");
        return 128 + sig;
    }
    if (video) {
        video->close();
        r.files.push_back(x.video_path);
    }
    if (progress)  // the rate the table's "fps (wall clock)" says
        progress->finish(std::to_string(r.frames) + " frames" + (r.frames_read_back ? " rendered and written" : ""),
                         r.profiler.wall_fps());
    if (r.frames_read_back && !opt.quiet)  // where the encoders are the bottleneck, this says so
        std::fprintf(stderr, "output: %.1f s of the frame loop went to read-back and waiting for the encoders (%.1f s after the last frame)\n",
                     r.output_s, r.output_drain_s);
    std::string title = graph_display_name(job.graph()) + " — " +
                        std::to_string(opt.size.x) + "x" + std::to_string(opt.size.y) + ", " +
                        std::to_string(r.frames) + " frames, " + std::to_string(scene.lines.line_count()) +
                        " lines, " + std::to_string(scene.lines.point_count()) + " points";
    std::printf("%s", r.profiler.table(title).c_str());
    mark_folders(x.folders, opt.graph_path);
    if (!r.files.empty())
        std::fprintf(stderr, "wrote %zu file(s), e.g. %s\n", r.files.size(), r.files.back().c_str());
    if (!x.report.empty()) {
        json meta = {{"graph", opt.graph_path}, {"renderer", rt.gl->renderer()}, {"size", {opt.size.x, opt.size.y}},
                     {"frames", r.frames}, {"data", scene.source}, {"variables", r.compiled.variables},
                     {"output_s", r.output_s}, {"output_drain_s", r.output_drain_s}};
        write_reports(r, x.report, meta);
    }
    // Last: a frame a pass could not draw whole is written anyway, and said here (exit 0).
    if (const std::string line = incomplete_frames_line(r); !line.empty()) std::fprintf(stderr, "%s\n", line.c_str());
    return 0;
}

int run(const std::vector<std::string>& argv) {
    Args a("render",
           "Renders a graph over a time range to image files (PNG by default, EXR for float outputs) and\n"
           "prints the per-pass timing table. Without arguments it renders the built-in aortic-arch\n"
           "phantom (generated on first use and cached) through the LineAO graph variant1_lineao.");
    RenderOptions opt;
    std::string graph, report, video_path;
    std::optional<TimeRange> time;
    std::optional<Shard> shard;
    double fps = 25;
    bool no_images = false, allow_empty = false;
    PluginOptions plugins;
    SceneOptions data;
    a.positional("GRAPH", graph, "graph file, or the name of a shipped graph (default: variant1_lineao; tracts_lineao for tracts, said on stderr)", false)
        .option("time", time, "T|A:B|A:B:STEP",
                "animation times in seconds (frames at A, A+STEP, ... <= B); default: the data's whole time span in 0.25 s steps");
    declare_size(a, opt.size, "output size in pixels");
    a.option("ssaa", opt.ssaa, "N",
             "supersampling for offline renders: render N x N larger (LineAO radii, filter widths and the "
             "level of detail scaled with it) and box-filter every frame down to --size (1..8)")
        .option("out", opt.out_dir, "DIR", "output folder ({out} in the graph's capture patterns)");
    declare_sets(a, opt.sets);
    declare_camera(a, opt.camera_path);
    a.option("orbit", opt.orbit_deg_per_s, "DEG_PER_S", "turntable: rotate the camera about the data at this rate");
    declare_timing(a, opt.timing);
    a.option("warmup", opt.warmup, "N", "frames rendered before timing starts (shader JIT on llvmpipe)")
        .option("report", report, "PREFIX", "also write PREFIX.csv, PREFIX.json and PREFIX.trace.json (Perfetto)")
        .option("video", video_path, "FILE.mp4", "also encode the frames to a video (needs ffmpeg on PATH)")
        .option("fps", fps, "N", "video frame rate")
        .option("shard", shard, "I/N", "render only frames k with k % N == I (0-based; Slurm array part), same file names")
        .flag("no-images", no_images, "do not write image files (timing runs)")
        .flag("quiet", opt.quiet, "no progress bar or notes")
        .flag("allow-empty-frames", allow_empty,
              "render the --time asked for even where it lies outside the data's time span (those frames are "
              "empty); without it such a time is an error naming the span");
    plugins.declare(a);
    data.declare(a);
    a.example("pathlet render", "the phantom through variant1_lineao.json into out/, with a timing table")
        .example("pathlet render isl --time 9 --size 1920x1080", "one frame of illuminated streamlines")
        .example("pathlet render --time 9 --size 1920x1080 --ssaa 4", "a figure: 4x4 supersampled")
        .example("pathlet render graphs/lineao_debug.json --time 9 --set lineao.samples=58",
                 "every intermediate map of one LineAO frame, with 58 samples")
        .example("pathlet render --data flow.vtp --mesh aorta.glb --time 0:18:0.04 --video flow.mp4",
                 "your own data, 25 fps, as a video")
        .example("pathlet render --set colormap=bundle --data bundles/",
                 "tracts, a file per bundle (a folder, files or a glob): tracts_lineao, a colour per bundle");
    if (!a.parse(argv)) return 0;
    if (video_path.empty()) a.unused_here({"fps"}, "without --video FILE (images have no frame rate)");

    if (graph.empty()) graph = data.default_graph(opt.quiet);
    opt.graph_path = resolve_graph_path(graph);  // an unknown name: one line, exit 2, before anything else
    if (shard) opt.shard_index = shard->index, opt.shard_count = shard->count;
    try {
        check_render_limits(opt);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--") + e.what());
    }
    if (opt.shard_count > 1 && !video_path.empty())
        throw UsageError("--video with --shard: each shard has only some frames; encode the joined frames (scripts/slurm/)");
    opt.write_images = !no_images;
    if (!video_path.empty() && !VideoWriter::available())
        std::fprintf(stderr, "warning: ffmpeg not found on PATH; --video ignored (images are still written)\n"),
            video_path.clear();

    Runtime rt;
    plugins.load(rt);
    // Nothing is made before the inputs are known good: the graph compiles (no GL) first, the
    // output places are checked without leaving a folder, then the data and the time.
    std::vector<std::string> folders;
    std::optional<RenderJob> job;
    try {
        job.emplace(rt, opt, Runtime::SetsFrom::user);
        if (opt.write_images) folders = capture_folders(job->compiled(), opt.out_dir, opt.size);
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
    if (opt.write_images) check_output_dir(opt.out_dir, "images (--out)", /*keep=*/false);
    if (!report.empty()) check_output_file(report + ".csv", "the timing report (--report)", false);
    if (!video_path.empty()) check_output_file(video_path, "the video (--video)", false);
    Scene scene = data.load(opt.quiet);
    job->set_time(time ? *time : default_time_range(scene));
    if (time) check_time_in_data(*time, shown(*time), scene, allow_empty);
    if (!opt.quiet) note_shared_folders(folders, opt.graph_path);
    try {
        return render_and_report(*job, rt, scene, {video_path, report, fps, folders});
    } catch (const GraphError& e) {
        return report_graph_error(e, rt);
    }
}

PATHLET_COMMAND("render", "render a graph over a time range to images/video, with a timing table", run);

}  // namespace
}  // namespace pathlet::cli
