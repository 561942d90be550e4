#include "renderer.hpp"

#include "util/atomic_file.hpp"

#include "executor.hpp"
#include "formats.hpp"
#include "image_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
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

std::string resolve_graph_path(const std::string& arg) {
    if (fs::exists(arg)) return arg;
    for (std::string name : {arg, arg + ".json"}) {
        fs::path p = fs::path(engine_share_dir()) / "graphs" / name;
        if (fs::exists(p)) return p.string();
    }
    return arg;  // the parser reports "file not found" with the name as given
}

// Warm-up by time (RenderOptions::warmup_seconds): blocks of frames of a quarter second each,
// finished on the GPU before the block's rate is taken, until `seconds` have passed and two
// blocks in a row agree within 5 %. A GPU's clock governor needs seconds of load to settle.
static void warm_up_by_time(double seconds, Profiler& profiler, const std::function<void()>& frame) {
    using clock = std::chrono::steady_clock;
    auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
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

RenderResult render(Runtime& rt, const Scene& scene, const RenderOptions& opt,
                    const std::function<void(const Executor&, size_t)>& on_frame) {
    RenderResult res;
    GraphFile g = rt.load_graph(opt.graph_path, opt.sets);
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
    Camera base = frame_bounds(bounds, render_size);
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
    if (count == 0) {  // more shards than frames: nothing to do
        res.profiler.release_gl();
        return res;
    }
    for (int w = 0; w < opt.warmup; ++w) exec.run_frame({index++, times[first], camera_at(times[first])});
    if (opt.warmup_seconds > 0)
        warm_up_by_time(opt.warmup_seconds, res.profiler,
                        [&] { exec.run_frame({index++, times[first], camera_at(times[first])}); });

    size_t done = 0;
    std::set<std::string> cleaned;  // output folders cleared of stale temps
    for (size_t i = 0; i < times.size(); ++i) {
        if (!mine(i)) continue;
        double t = times[i];
        exec.run_frame({index++, t, camera_at(t)});
        for (const auto& out : cg.outputs) {
            if (out.capture.empty() && !opt.on_image) continue;
            int r = cg.find_resource(out.resource);
            const auto& rd = cg.resources[size_t(r)];
            if (rd.kind != PinKind::Texture) continue;
            Texture tex = exec.texture(out.resource);
            Image img = box_downsample(read_texture(tex.id, tex.width, tex.height, 0, 4), ssaa);
            if (opt.write_images && !out.capture.empty()) {
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
                write_image(file, img);
                res.files.push_back(file);
            }
            if (opt.on_image && &out == &cg.outputs.front()) opt.on_image(img);
        }
        if (on_frame) on_frame(exec, i);
        if (opt.on_progress) opt.on_progress(++done, count);
    }
    res.frames = count;
    res.profiler.release_gl();  // collects frames still in flight, then frees the queries
    return res;
}

}  // namespace pathlet
