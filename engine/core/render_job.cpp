#include "render_job.hpp"

#include "executor.hpp"
#include "formats.hpp"
#include "frames/async_output.hpp"
#include "image_io.hpp"
#include "util/atomic_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Warm-up by time (RenderOptions::warmup_seconds): blocks of frames of a quarter second each,
// finished on the GPU before the block's rate is taken, until `seconds` have passed and two
// blocks in a row agree within 5 %. A GPU's clock governor needs seconds of load to settle.
void warm_up_by_time(double seconds, Profiler& profiler, const std::function<void()>& frame) {
    using clock = std::chrono::steady_clock;
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
        } while (seconds_since(b0) < block);
        glFinish();  // warm-up only: the block's frames done, so its rate is the GPU's
        const double rate = double(n) / seconds_since(b0);
        settled = previous > 0 && std::fabs(rate / previous - 1.0) < 0.05;
        if ((settled && seconds_since(start) >= seconds) || seconds_since(start) >= cap) break;
        previous = rate;
    }
    profiler.end_warmup(seconds_since(start), settled);
}

}  // namespace

RenderJob::RenderJob(Runtime& rt, RenderOptions opt, Runtime::SetsFrom from, std::vector<ReadBack> read_backs)
    : rt_(rt), opt_(std::move(opt)), read_backs_(std::move(read_backs)) {
    graph_ = rt_.load_graph(opt_.graph_path, opt_.sets, from);
    // Supersampling: the graph runs at N x N the size with its pixel-measured parameters scaled
    // (PassContext::pixel_scale), and every captured frame is box-filtered back to `size`.
    const int ssaa = std::max(1, opt_.ssaa);
    compiled_ = compile_graph(graph_, rt_.registry, opt_.size * ssaa, float(ssaa));
    for (auto& rb : read_backs_) {
        std::string why;
        const int r = compiled_.resolve(rb.resource, &why);
        if (r < 0) throw std::invalid_argument(why);
        rb.resource = compiled_.resources[size_t(r)].name;
        opt_.keep.push_back(rb.resource);  // out of the pool: still theirs after the frame
    }
    keep_resources(compiled_, opt_.keep);
}

// One run of the job, in the order it happens: the GPU side set up, the frames scheduled
// (times, repeats, shards), warm-up, the frames with their captures, the end.
class RenderJob::Loop {
public:
    Loop(RenderJob& job, const Scene& scene, const std::function<void(const Executor&, size_t)>& on_frame)
        : job_(job), opt_(job.opt_), cg_(job.compiled_), scene_(scene), on_frame_(on_frame),
          render_size_(opt_.size * std::max(1, opt_.ssaa)), gl_(job.rt_.ensure_gl(opt_.quiet)) {}

    RenderResult run() {
        if (!opt_.quiet) {
            for (const auto& n : job_.graph_.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
            for (const auto& c : cg_.culled) std::fprintf(stderr, "note: pass '%s' culled: %s\n", c.name.c_str(), c.reason.c_str());
        }
        res_.compiled = cg_;
        set_up();
        schedule();
        if (count_ == 0 || stopped()) {  // more shards than frames, or stopped while setting up
            res_.interrupted = count_ > 0;
            res_.profiler.release_gl();
            return std::move(res_);
        }
        warm_up();
        frames();
        finish();
        return std::move(res_);
    }

private:
    void set_up() {
        gpu_.upload(scene_);
        res_.profiler.init(opt_.timing, gl_.renderer());
        res_.profiler.set_warmup_frames(opt_.warmup);
        exec_.emplace(gl_, cg_, gpu_, &res_.profiler);
        exec_->setup();
        if (!opt_.camera_path.empty()) path_ = CameraPath::load(opt_.camera_path);
        bounds_ = scene_.bounds();
        // The data fills the frame; an orbit stands back far enough that it stays whole at every
        // angle of the turn.
        base_ = opt_.orbit_deg_per_s != 0.0 ? frame_bounds_orbit(bounds_, framing_points(scene_, 20000), render_size_)
                                            : frame_points(bounds_, framing_points(scene_), render_size_);
    }

    Camera camera_at(double t) const {
        Camera c = opt_.camera_path.empty() ? base_ : path_.at(t, bounds_, render_size_);
        if (opt_.orbit_deg_per_s != 0.0) c = orbit(c, opt_.orbit_deg_per_s, t, bounds_, render_size_);
        return c;
    }

    // The frames' times (each repeated), and which of them are this shard's.
    void schedule() {
        for (double t : opt_.time.times())
            for (int k = 0; k < std::max(1, opt_.repeat); ++k) times_.push_back(t);
        while (first_ < times_.size() && !mine(first_)) ++first_;
        for (size_t i = 0; i < times_.size(); ++i) count_ += mine(i);
    }
    bool mine(size_t i) const { return int(i % size_t(std::max(1, opt_.shard_count))) == opt_.shard_index; }
    bool stopped() const { return opt_.stop && opt_.stop(); }

    // Warm-up frames (JIT compiles shader variants on first use) are rendered, not written.
    void warm_up() {
        const double t = times_[first_];
        for (int w = 0; w < opt_.warmup; ++w) exec_->run_frame({index_++, t, camera_at(t)});
        if (opt_.warmup_seconds > 0)
            warm_up_by_time(opt_.warmup_seconds, res_.profiler, [&] { exec_->run_frame({index_++, t, camera_at(t)}); });
    }

    void frames() {
        // 0 done before the first frame: a caller's clock (the progress line's rate) starts with the loop.
        if (opt_.on_frames) opt_.on_frames(0, 0, count_);
        for (size_t i = 0; i < times_.size(); ++i) {
            if (!mine(i)) continue;
            if (stopped()) {
                res_.interrupted = true;
                break;
            }
            const double t = times_[i];
            frame_number_[index_] = i;
            exec_->run_frame({index_++, t, camera_at(t)});
            const auto t0 = std::chrono::steady_clock::now();
            std::vector<AsyncOutput::Capture> captures = captures_of(i);
            if (!captures.empty()) output().capture(captures);
            if (output_) output_->poll();  // what the GPU has copied goes to the writers, no waiting
            res_.output_s += seconds_since(t0);
            if (on_frame_) on_frame_(*exec_, i);
            ++done_;
            if (opt_.on_progress) opt_.on_progress(done_, count_);
            if (opt_.on_frames) opt_.on_frames(done_, written(), count_);
        }
    }

    // What frame i's pixels go to: files of the graph's outputs, the caller's image, the
    // read-backs. Nothing that nobody uses is read back.
    std::vector<AsyncOutput::Capture> captures_of(size_t i) {
        std::vector<AsyncOutput::Capture> captures;
        const std::string gname = graph_display_name(job_.graph_);
        for (const auto& out : cg_.outputs) {
            const bool to_file = opt_.write_images && !out.capture.empty();
            const bool to_image = opt_.on_image && &out == &cg_.outputs.front();
            if (!to_file && !to_image) continue;
            const auto& rd = cg_.resources[size_t(cg_.find_resource(out.resource))];
            if (rd.kind != PinKind::Texture) continue;
            AsyncOutput::Capture c;
            c.what = "output '" + out.resource + "'";
            c.tex = exec_->texture(out.resource);
            c.to_image = to_image;
            if (to_file) c.file = output_file(out, rd, gname, i);
            captures.push_back(std::move(c));
        }
        for (const auto& rb : job_.read_backs_) {
            AsyncOutput::Capture c;
            c.what = "resource '" + rb.resource + "'";
            c.tex = exec_->texture(rb.resource);
            // Render-size textures follow --ssaa down to the picture; others stay as they are.
            if (c.tex.width != render_size_.x || c.tex.height != render_size_.y) c.factor = 1;
            c.sink = [take = rb.take, i](const Image& img) { take(i, img); };
            captures.push_back(std::move(c));
        }
        return captures;
    }

    std::string output_file(const OutputDecl& out, const CompiledResource& rd, const std::string& gname, size_t i) {
        std::string file = expand_pattern(out.capture,
                                          {{"out", opt_.out_dir}, {"graph", gname}, {"output", out.resource},
                                           {"size", std::to_string(opt_.size.x) + "x" + std::to_string(opt_.size.y)}},
                                          i);
        // A pattern without an extension: EXR keeps float outputs exact, PNG for the rest.
        // (Asked of the pattern: expanded names like "soft.tmp_000" contain dots.)
        if (fs::path(out.capture).extension().empty()) {
            const FormatInfo* fi = find_format(rd.internal_format);
            file += fi && (fi->is_float || fi->depth) ? ".exr" : ".png";
        }
        ensure_parent_dir(file);
        // Once per folder: temps of a render that was killed are not left lying around.
        if (cleaned_.insert(fs::path(file).parent_path().string()).second)
            remove_stale_temps(fs::path(file).parent_path().string());
        res_.files.push_back(file);
        return file;
    }

    // Made on the first frame something uses: renders nobody reads (bench, --no-images) have none.
    AsyncOutput& output() {
        if (!output_) {
            AsyncOutput::Options o;
            o.ssaa = std::max(1, opt_.ssaa);
            o.ring_depth = size_t(std::max(1, opt_.readback_frames));
            o.threads = opt_.writer_threads;
            o.max_queued = size_t(std::max(0, opt_.max_queued_images));
            o.on_image = opt_.on_image;
            o.quiet = opt_.quiet;
            output_.emplace(o);
        }
        return *output_;
    }
    size_t written() const { return output_ ? output_->frames_written() : 0; }

    void finish() {
        exec_->finish();  // late counts waited for: every incomplete frame is known
        for (uint64_t k : exec_->incomplete_frames())
            if (auto it = frame_number_.find(k); it != frame_number_.end()) res_.incomplete_frames.push_back(it->second);
        std::sort(res_.incomplete_frames.begin(), res_.incomplete_frames.end());
        const auto t0 = std::chrono::steady_clock::now();
        if (output_) output_->finish();
        res_.output_drain_s = seconds_since(t0);
        res_.output_s += res_.output_drain_s;
        if (opt_.on_frames) opt_.on_frames(done_, written(), count_);
        res_.frames = done_;
        res_.frames_read_back = output_ ? output_->frames_captured() : 0;
        res_.profiler.release_gl();  // collects frames still in flight, then frees the queries
    }

    RenderJob& job_;
    const RenderOptions& opt_;
    const CompiledGraph& cg_;
    const Scene& scene_;
    const std::function<void(const Executor&, size_t)>& on_frame_;
    const glm::ivec2 render_size_;
    GlContext& gl_;
    RenderResult res_;
    GpuScene gpu_;
    std::optional<Executor> exec_;
    CameraPath path_;
    Bounds bounds_;
    Camera base_;
    std::vector<double> times_;
    size_t first_ = 0, count_ = 0, done_ = 0;
    uint64_t index_ = 0;
    std::optional<AsyncOutput> output_;
    std::set<std::string> cleaned_;           // output folders cleared of stale temps
    std::map<uint64_t, size_t> frame_number_;  // executor index -> output frame number (not warm-up)
};

RenderResult RenderJob::run(const Scene& scene, const std::function<void(const Executor&, size_t)>& on_frame) {
    return Loop(*this, scene, on_frame).run();
}

}  // namespace pathlet
