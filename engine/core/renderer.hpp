// A render job: compile a graph for a size, run it over a time range with a camera, write
// the captured outputs (PNG/EXR, optional MP4) and collect per-pass timings. Shared by
// `pathlet render`, `pathlet bench`, the tests and the benchmarks.
#pragma once

#include "camera.hpp"
#include "image_io.hpp"
#include "graph/graph_model.hpp"
#include "profiler/profiler.hpp"
#include "runtime.hpp"

#include <pathlet/gpu_scene.hpp>

#include <functional>
#include <string>
#include <vector>

namespace pathlet {

struct TimeRange {
    double start = 0, end = 0, step = 0.04;
    std::vector<double> times() const;  // start, start+step, ... <= end (at least one)
};
// "t", "a:b" (25 frames per second) or "a:b:step"; throws std::invalid_argument with a hint.
TimeRange parse_time_range(const std::string& text);
// What a render without a time shows: the data's whole span in 0.25 s steps, or one frame for
// lines without time (streamlines are drawn whole: more frames would be the same picture).
TimeRange default_time_range(const Scene& scene);
// What a bench without a time measures: one moment, the middle of the data's span (the study
// phantom's 9 s; 0 for lines without time).
TimeRange default_bench_time(const Scene& scene);
// What quality without a time measures: 11 frames 0.04 s apart from the middle of the span
// (the study phantom's 9..9.4 s), moved back to end within it; a shorter span: 11 frames over it.
TimeRange default_quality_time(const Scene& scene);
// What a command says when it picked the time: "time 2 s (the middle of SOURCE's 0..4 s, as no
// time was given)"; `how` says how it was picked ("the middle", "11 frames from the middle").
std::string picked_time_note(const TimeRange& t, const Scene& scene, const std::string& how);
glm::ivec2 parse_size(const std::string& text);  // "1280x720"

struct RenderOptions {
    std::string graph_path;
    std::vector<std::string> sets;   // --set overrides
    glm::ivec2 size{1280, 720};
    int ssaa = 1;                    // render ssaa x ssaa times larger, box-filter down to `size`
    // Resources kept out of the pool, so their content is still theirs after the frame (for
    // reading intermediates back: tests, debugging).
    std::vector<std::string> keep;
    TimeRange time;
    int repeat = 1;                  // render each time this often (timing runs of one moment)
    std::string out_dir = "out";     // {out} in capture patterns
    std::string camera_path;         // keyframed JSON; "" = frame the data
    double orbit_deg_per_s = 0.0;
    TimingBackend timing = TimingBackend::Auto;
    int warmup = 2;                  // frames rendered first and not timed or written
    // Then, when > 0, warm-up by time: frames until at least this long has passed and the frame
    // rate of the last two quarter-second blocks agrees within 5 % (a GPU's clock has settled),
    // at most max(5 s, 4x this). `bench` uses 1 s on a GPU (0 on software renderers).
    double warmup_seconds = 0;
    bool write_images = true;
    bool quiet = false;
    // What the caller sees while it runs (the render command's progress bar and video encoder):
    // frames done of the total, and the first output of every written frame at `size`.
    // on_image runs on a writer thread, in frame order, one call at a time.
    std::function<void(size_t done, size_t total)> on_progress;
    std::function<void(const Image& first_output)> on_image;
    // Frames rendered and frames written (their files renamed into place and on_image done) of
    // the total, on the render thread after every frame and once when everything is written.
    std::function<void(size_t rendered, size_t written, size_t total)> on_frames;
    // Polled before every frame: true ends the render early (RenderResult::interrupted); the
    // frames rendered until then are still written, and nothing half-written stays.
    std::function<bool()> stop;
    // The output side (frames/async_output.hpp): only what a file or on_image uses is read
    // back, through pixel-pack buffers with `readback_frames` frames in flight, and encoded on
    // `writer_threads` threads (0: min(4, cores)) with at most `max_queued_images` images
    // waiting (0: threads + 2; the render thread waits beyond that).
    int readback_frames = 3, writer_threads = 0, max_queued_images = 0;
    // Frame i is rendered when i % shard_count == shard_index (render --shard I/N); names stay
    // those of the whole sequence, so the shards' files together are the unsharded output.
    int shard_index = 0, shard_count = 1;
};
// The limits of a render's options, for every caller (the command, Python): ssaa 1..8, size x
// ssaa at most 16384 pixels a side, warmup >= 0. std::invalid_argument naming the option.
void check_render_limits(const RenderOptions& opt);

struct RenderResult {
    size_t frames = 0;               // rendered (fewer than asked when interrupted)
    bool interrupted = false;        // RenderOptions::stop ended it
    size_t frames_read_back = 0;     // frames whose pixels a file or on_image used (none: no read-back)
    // The render thread's time on the output side: queuing copies, waiting for a full ring or
    // for the writers (back-pressure), and the final wait until every file is written.
    double output_s = 0, output_drain_s = 0;
    std::vector<std::string> files;  // written images/videos
    // Frames a pass reported as incomplete (fragments dropped), numbered as the output files are,
    // ascending; counts still in flight at the end were waited for (Executor::finish()).
    std::vector<size_t> incomplete_frames;
    Profiler profiler;
    CompiledGraph compiled;
};

// Throws GraphError (bad graph), PassError (a pass failed), std::runtime_error (I/O).
// `on_frame` (optional) sees the executor after each written frame (tests read textures).
class Executor;
RenderResult render(Runtime& rt, const Scene& scene, const RenderOptions& opt,
                    const std::function<void(const Executor&, size_t frame)>& on_frame = {});

// "incomplete frames: N of M (3, 4, 11)" for a render where a pass dropped anything, else "":
// the last stderr line of render, bench and Python's render (the frames are written anyway).
std::string incomplete_frames_line(const RenderResult& r);

// Name of a graph: its "name" field, else the file stem.
std::string graph_display_name(const GraphFile& g);
// Resolves a graph argument: a path, or a bare name found in the installed graphs folder;
// GraphNotFound (with a did-you-mean) for neither (graph_model.hpp's find_graph_file).
std::string resolve_graph_path(const std::string& arg);

}  // namespace pathlet
