#include "renderer.hpp"

#include "util/atomic_file.hpp"

#include "executor.hpp"
#include "formats.hpp"
#include "frames/async_output.hpp"
#include "image_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;

namespace pathlet {

std::vector<double> TimeRange::times() const {
    std::vector<double> t;
    if (!(step > 0) || end <= start) return {start};
    size_t n = size_t(std::floor((end - start) / step + 1e-9)) + 1;
    for (size_t i = 0; i < n; ++i) t.push_back(start + double(i) * step);
    return t;
}

TimeRange default_time_range(const Scene& scene) {
    if (scene.lines.timeless) return {0, 0, 0.25};
    return {scene.lines.time_min(), scene.lines.time_max(), 0.25};
}

TimeRange default_bench_time(const Scene& scene) {
    if (scene.lines.timeless) return {0, 0, 0};
    const double mid = 0.5 * (scene.lines.time_min() + scene.lines.time_max());
    return {mid, mid, 0};
}

TimeRange default_quality_time(const Scene& scene) {
    constexpr double kStep = 0.04, kSpan = 10 * kStep;  // 11 frames
    const double t0 = scene.lines.timeless ? 0.0 : scene.lines.time_min();
    const double t1 = scene.lines.timeless ? 0.0 : scene.lines.time_max();
    if (t1 - t0 < kSpan) return {t0, t1, t1 > t0 ? (t1 - t0) / 10 : kStep};
    const double start = std::min(0.5 * (t0 + t1), t1 - kSpan);
    return {start, start + kSpan, kStep};
}

std::string picked_time_note(const TimeRange& t, const Scene& scene, const std::string& how) {
    char b[256];
    const std::vector<double> times = t.times();
    if (times.size() == 1)
        std::snprintf(b, sizeof b, "time %g s", t.start);
    else
        std::snprintf(b, sizeof b, "time %g..%g s (%zu frames)", t.start, times.back(), times.size());
    std::string s = b;
    if (scene.lines.timeless) return s + " (" + scene.source + " has no time)";
    std::snprintf(b, sizeof b, "%g..%g s", scene.lines.time_min(), scene.lines.time_max());
    return s + " (" + how + " of " + scene.source + "'s " + b + ", as no time was given)";
}

TimeRange parse_time_range(const std::string& text) {
    std::vector<double> parts;
    size_t pos = 0;
    try {
        while (pos <= text.size()) {
            size_t c = text.find(':', pos);
            std::string tok = text.substr(pos, c == std::string::npos ? std::string::npos : c - pos);
            size_t used = 0;
            parts.push_back(std::stod(tok, &used));
            if (used != tok.size()) throw std::invalid_argument("");
            if (c == std::string::npos) break;
            pos = c + 1;
        }
    } catch (const std::exception&) {
        throw std::invalid_argument("--time '" + text + "': expected T, START:END or START:END:STEP in seconds (e.g. 0:18:0.04)");
    }
    TimeRange r;
    if (parts.size() == 1) {
        r.start = r.end = parts[0];
    } else if (parts.size() == 2 || parts.size() == 3) {
        r.start = parts[0];
        r.end = parts[1];
        r.step = parts.size() == 3 ? parts[2] : 0.04;
        if (!(r.step > 0)) throw std::invalid_argument("--time '" + text + "': the step must be positive");
        if (r.end < r.start) throw std::invalid_argument("--time '" + text + "': END is before START");
    } else {
        throw std::invalid_argument("--time '" + text + "': expected T, START:END or START:END:STEP");
    }
    return r;
}

glm::ivec2 parse_size(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
        w > 16384 || h > 16384)
        throw std::invalid_argument("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720 (1..16384)");
    return {w, h};
}

void check_render_limits(const RenderOptions& opt) {
    if (opt.ssaa < 1 || opt.ssaa > 8) throw std::invalid_argument("ssaa must be 1..8 (got " + std::to_string(opt.ssaa) + ")");
    if (opt.size.x * opt.ssaa > 16384 || opt.size.y * opt.ssaa > 16384)
        throw std::invalid_argument("ssaa x size exceeds 16384 pixels on a side (" + std::to_string(opt.size.x) + "x" +
                                    std::to_string(opt.size.y) + " x " + std::to_string(opt.ssaa) + "); lower one of them");
    if (opt.warmup < 0) throw std::invalid_argument("warmup must be >= 0 (got " + std::to_string(opt.warmup) + ")");
}

std::string graph_display_name(const GraphFile& g) {
    return g.name.empty() ? fs::path(g.path).stem().string() : g.name;
}

std::string resolve_graph_path(const std::string& arg) { return find_graph_file(arg); }

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

// Warm-up by time (RenderOptions::warmup_seconds): blocks of frames of a quarter second each,
// finished on the GPU before the block's rate is taken, until `seconds` have passed and two
// blocks in a row agree within 5 %. A GPU's clock governor needs seconds of load to settle.
static void warm_up_by_time(double seconds, Profiler& profiler, const std::function<void()>& frame) {
    using clock = std::chrono::steady_clock;
    const auto since = seconds_since;
    const auto start = clock::now();
    const double cap = std::max(5.0, 4.0 * seconds), block = 0.25;
    double previous = 0;
    bool settled = false;
    while (true) {
        const auto b0 = clock::now();
        int n = 0;
        do {
            frame();
            ++n;
        } while (since(b0) < block);
        glFinish();  // warm-up only: the block's frames done, so its rate is the GPU's
        const double rate = double(n) / since(b0);
        settled = previous > 0 && std::fabs(rate / previous - 1.0) < 0.05;
        if ((settled && since(start) >= seconds) || since(start) >= cap) break;
        previous = rate;
    }
    profiler.end_warmup(since(start), settled);
}

std::string incomplete_frames_line(const RenderResult& r) {
    if (r.incomplete_frames.empty()) return "";
    std::string list;
    for (size_t f : r.incomplete_frames) list += (list.empty() ? "" : ", ") + std::to_string(f);
    return "incomplete frames: " + std::to_string(r.incomplete_frames.size()) + " of " + std::to_string(r.frames) +
           " (" + list + ")";
}

RenderResult render(Runtime& rt, const Scene& scene, const RenderOptions& opt,
                    const std::function<void(const Executor&, size_t)>& on_frame) {
    RenderResult res;
    GraphFile g = rt.load_graph(opt.graph_path, opt.sets);
    if (!opt.quiet)
        for (const auto& n : g.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
    for (auto& r : g.resources)
        if (std::find(opt.keep.begin(), opt.keep.end(), r.name) != opt.keep.end()) r.persistent = true;
    // Supersampling: the graph runs at N x N the size with its pixel-measured parameters scaled
    // (PassContext::pixel_scale), and every captured frame is box-filtered back to `size`.
    const int ssaa = std::max(1, opt.ssaa);
    const glm::ivec2 render_size = opt.size * ssaa;
    res.compiled = compile_graph(g, rt.registry, render_size);
    res.compiled.pixel_scale = float(ssaa);
    const CompiledGraph& cg = res.compiled;
    if (!opt.quiet)
        for (const auto& c : cg.culled) std::fprintf(stderr, "note: pass '%s' culled: %s\n", c.name.c_str(), c.reason.c_str());

    GlContext& gl = rt.ensure_gl(opt.quiet);
    GpuScene gpu;
    gpu.upload(scene);
    res.profiler.init(opt.timing, gl.renderer());
    res.profiler.set_warmup_frames(opt.warmup);
    Executor exec(gl, cg, gpu, &res.profiler);
    exec.setup();

    CameraPath path;
    if (!opt.camera_path.empty()) path = CameraPath::load(opt.camera_path);
    Bounds bounds = scene.bounds();
    // The data fills the frame; an orbit stands back far enough that it stays whole at every
    // angle of the turn.
    Camera base = opt.orbit_deg_per_s != 0.0 ? frame_bounds_orbit(bounds, framing_points(scene, 20000), render_size)
                                             : frame_points(bounds, framing_points(scene), render_size);
    auto camera_at = [&](double t) {
        Camera c = opt.camera_path.empty() ? base : path.at(t, bounds, render_size);
        if (opt.orbit_deg_per_s != 0.0) c = orbit(c, opt.orbit_deg_per_s, t, bounds, render_size);
        return c;
    };

    std::string gname = graph_display_name(g);
    std::vector<double> times;
    for (double t : opt.time.times())
        for (int k = 0; k < std::max(1, opt.repeat); ++k) times.push_back(t);
    // Warm-up frames (JIT compiles shader variants on first use) are rendered, not written.
    uint64_t index = 0;
    const int shards = std::max(1, opt.shard_count);
    auto mine = [&](size_t i) { return int(i % size_t(shards)) == opt.shard_index; };
    size_t first = 0, count = 0;
    while (first < times.size() && !mine(first)) ++first;
    for (size_t i = 0; i < times.size(); ++i) count += mine(i);
    auto stopped = [&] { return opt.stop && opt.stop(); };
    if (count == 0 || stopped()) {  // more shards than frames, or stopped while setting up
        res.interrupted = count > 0;
        res.profiler.release_gl();
        return res;
    }
    for (int w = 0; w < opt.warmup; ++w) exec.run_frame({index++, times[first], camera_at(times[first])});
    if (opt.warmup_seconds > 0)
        warm_up_by_time(opt.warmup_seconds, res.profiler,
                        [&] { exec.run_frame({index++, times[first], camera_at(times[first])}); });

    // Made on the first frame something uses: renders nobody reads (bench, --no-images) have none.
    std::optional<AsyncOutput> output;
    AsyncOutput::Options out_opt;
    out_opt.ssaa = ssaa;
    out_opt.ring_depth = size_t(std::max(1, opt.readback_frames));
    out_opt.threads = opt.writer_threads;
    out_opt.max_queued = size_t(std::max(0, opt.max_queued_images));
    out_opt.on_image = opt.on_image;
    out_opt.quiet = opt.quiet;
    auto written = [&] { return output ? output->frames_written() : size_t(0); };

    size_t done = 0;
    std::set<std::string> cleaned;  // output folders cleared of stale temps
    std::map<uint64_t, size_t> frame_number;  // executor index -> output frame number (not warm-up)
    // 0 done before the first frame: a caller's clock (the progress line's rate) starts with the loop.
    if (opt.on_frames) opt.on_frames(0, 0, count);
    for (size_t i = 0; i < times.size(); ++i) {
        if (!mine(i)) continue;
        if (stopped()) {
            res.interrupted = true;
            break;
        }
        double t = times[i];
        frame_number[index] = i;
        exec.run_frame({index++, t, camera_at(t)});
        std::vector<AsyncOutput::Capture> captures;
        for (const auto& out : cg.outputs) {
            const bool to_file = opt.write_images && !out.capture.empty();
            const bool to_image = opt.on_image && &out == &cg.outputs.front();
            if (!to_file && !to_image) continue;  // nobody uses its pixels: not read back
            int r = cg.find_resource(out.resource);
            const auto& rd = cg.resources[size_t(r)];
            if (rd.kind != PinKind::Texture) continue;
            AsyncOutput::Capture c;
            c.what = "output '" + out.resource + "'";
            c.tex = exec.texture(out.resource);
            c.to_image = to_image;
            if (to_file) {
                std::string file = expand_pattern(out.capture,
                                                  {{"out", opt.out_dir}, {"graph", gname}, {"output", out.resource},
                                                   {"size", std::to_string(opt.size.x) + "x" + std::to_string(opt.size.y)}},
                                                  i);
                // A pattern without an extension: EXR keeps float outputs exact, PNG for the rest.
                // (Asked of the pattern: expanded names like "soft.tmp_000" contain dots.)
                if (fs::path(out.capture).extension().empty()) {
                    const FormatInfo* fi = find_format(rd.internal_format);
                    file += fi && (fi->is_float || fi->depth) ? ".exr" : ".png";
                }
                ensure_parent_dir(file);
                // Once per folder: temps of a render that was killed are not left lying around.
                if (cleaned.insert(fs::path(file).parent_path().string()).second)
                    remove_stale_temps(fs::path(file).parent_path().string());
                c.file = file;
                res.files.push_back(file);
            }
            captures.push_back(std::move(c));
        }
        const auto t0 = std::chrono::steady_clock::now();
        if (!captures.empty()) {
            if (!output) output.emplace(out_opt);
            output->capture(captures);
        }
        if (output) output->poll();  // what the GPU has copied goes to the writers, no waiting
        res.output_s += seconds_since(t0);
        if (on_frame) on_frame(exec, i);
        ++done;
        if (opt.on_progress) opt.on_progress(done, count);
        if (opt.on_frames) opt.on_frames(done, written(), count);
    }
    exec.finish();  // late counts waited for: every incomplete frame is known
    for (uint64_t k : exec.incomplete_frames())
        if (auto it = frame_number.find(k); it != frame_number.end()) res.incomplete_frames.push_back(it->second);
    std::sort(res.incomplete_frames.begin(), res.incomplete_frames.end());
    const auto t0 = std::chrono::steady_clock::now();
    if (output) output->finish();
    res.output_drain_s = seconds_since(t0);
    res.output_s += res.output_drain_s;
    if (opt.on_frames) opt.on_frames(done, written(), count);
    res.frames = done;
    res.frames_read_back = output ? output->frames_captured() : 0;
    res.profiler.release_gl();  // collects frames still in flight, then frees the queries
    return res;
}

}  // namespace pathlet
