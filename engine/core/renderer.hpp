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
    std::function<void(size_t done, size_t total)> on_progress;
    std::function<void(const Image& first_output)> on_image;
    // Frame i is rendered when i % shard_count == shard_index (render --shard I/N); names stay
    // those of the whole sequence, so the shards' files together are the unsharded output.
    int shard_index = 0, shard_count = 1;
};
// The limits of a render's options, for every caller (the command, Python): ssaa 1..8, size x
// ssaa at most 16384 pixels a side, warmup >= 0. std::invalid_argument naming the option.
void check_render_limits(const RenderOptions& opt);

struct RenderResult {
    size_t frames = 0;
    std::vector<std::string> files;  // written images/videos
    Profiler profiler;
    CompiledGraph compiled;
};

// Throws GraphError (bad graph), PassError (a pass failed), std::runtime_error (I/O).
// `on_frame` (optional) sees the executor after each written frame (tests read textures).
class Executor;
RenderResult render(Runtime& rt, const Scene& scene, const RenderOptions& opt,
                    const std::function<void(const Executor&, size_t frame)>& on_frame = {});

// Name of a graph: its "name" field, else the file stem.
std::string graph_display_name(const GraphFile& g);
// Resolves a graph argument: a path, or a bare name found in the installed graphs folder.
std::string resolve_graph_path(const std::string& arg);

}  // namespace pathlet
