#include "transparency.hpp"

#include "camera.hpp"
#include "executor.hpp"
#include "graph/graph_model.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace pathlet::quality {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr uint32_t kEnd = 0xFFFFFFFFu;  // OIT_END and OO_END
constexpr double kOpaque = 0.99;        // resolve_list stops compositing here

// The resources of the graph's OIT and of its opacity optimization, by name.
struct Oit {
    std::string why_not;
    std::string resolve, fill;                      // pass names
    std::string heads, nodes, counter;              // the final lists
    std::vector<std::string> oo_lists, oo_targets;  // opacity_lists' lists, opacity_resolve's targets
};

std::string bound(const json& pass, const char* side, const char* pin) {
    if (!pass.contains(side) || !pass[side].contains(pin) || !pass[side][pin].is_string()) return "";
    return pass[side][pin].get<std::string>();
}

Oit find_oit(const json& g) {
    Oit o;
    for (const json& p : g["passes"])
        if (p.value("type", "") == "resolve_list" && p.value("enabled", true)) {
            o.resolve = p.value("name", "");
            o.heads = bound(p, "inputs", "heads");
            o.nodes = bound(p, "inputs", "nodes");
            break;
        }
    if (o.resolve.empty()) {
        o.why_not = "no OIT in this graph (no resolve_list pass)";
        return o;
    }
    for (const json& p : g["passes"])
        if (bound(p, "outputs", "nodes") == o.nodes && !o.nodes.empty()) {
            o.fill = p.value("name", "");
            o.counter = bound(p, "inputs", "counter");
        }
    if (o.heads.empty() || o.nodes.empty() || o.counter.empty() || o.heads.find('.') != std::string::npos ||
        o.nodes.find('.') != std::string::npos)
        o.why_not = "resolve_list's heads and nodes (and the counter of the pass that fills them) must be named resources";
    for (const json& p : g["passes"]) {
        if (p.value("type", "") == "opacity_lists" && !bound(p, "outputs", "lists").empty())
            o.oo_lists.push_back(bound(p, "outputs", "lists"));
        if (p.value("type", "") == "opacity_resolve" && !bound(p, "outputs", "targets").empty())
            o.oo_targets.push_back(bound(p, "outputs", "targets"));
    }
    return o;
}

template <class T>
std::vector<T> read_buffer(const Buffer& b, size_t count, size_t offset_bytes = 0) {
    std::vector<T> v(count);
    if (count) glGetNamedBufferSubData(b.id, GLintptr(offset_bytes), GLsizeiptr(count * sizeof(T)), v.data());
    return v;
}

float bits_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Where each line's window lies: per line the first and last point of the segments that
// overlap [t0, t1] (every point when the lines are drawn whole).
struct WindowRanges {
    std::vector<uint32_t> first, last;  // point indices, last >= first + 1 for a drawable piece
};
WindowRanges window_ranges(const Pathlines& pl, double t0, double t1, bool whole) {
    WindowRanges w;
    for (const LineRange& r : pl.lines) {
        uint32_t a = r.first, b = r.first + (r.count ? r.count - 1 : 0);
        if (!whole && r.count >= 2) {
            const float* t = pl.time.data();
            const uint32_t e = r.first + r.count;
            uint32_t lo = uint32_t(std::lower_bound(t + r.first, t + e, float(t0)) - t);
            uint32_t hi = uint32_t(std::upper_bound(t + r.first, t + e, float(t1)) - t);
            a = lo > r.first ? lo - 1 : r.first;
            b = std::min(hi, e - 1);
            if (hi == r.first || lo == e) b = a;  // the window misses the line
        }
        w.first.push_back(a);
        w.last.push_back(b);
    }
    return w;
}

// The data segment (its first point) of line `line` nearest to `p` within the window.
int64_t nearest_segment(const Pathlines& pl, const WindowRanges& w, uint32_t line, const glm::vec3& p) {
    if (line >= w.first.size() || w.last[line] <= w.first[line]) return -1;
    double best = std::numeric_limits<double>::infinity();
    int64_t at = -1;
    for (uint32_t k = w.first[line]; k < w.last[line]; ++k) {
        const glm::vec3 a = pl.position[k], d = pl.position[k + 1] - a;
        const float dd = glm::dot(d, d);
        const float s = dd > 0.0f ? std::clamp(glm::dot(p - a, d) / dd, 0.0f, 1.0f) : 0.0f;
        const glm::vec3 q = a + s * d - p;
        const double dist = glm::dot(q, q);
        if (dist < best) best = dist, at = k;
    }
    return at;
}


// The lists of one frame as read back: per pixel the head node, and the nodes (colour, depth
// bits, next, line id).
struct FrameLists {
    int width = 0, height = 0;
    std::vector<uint32_t> heads;
    std::vector<glm::uvec4> nodes;
};

// One measurement, in stage order: the focus (the fastest segments over the whole data), the
// render's options (the lists kept for reading back), then per frame: read the lists, place and
// composite every pixel's fragments, add the frame's per-segment measures; at the end, the
// summary of all frames.
class Measurement {
public:
    Measurement(const Scene& scene, const TransparencyOptions& q, Oit oit, TransparencyResult& res)
        : scene_(scene), pl_(scene.lines), q_(q), oit_(std::move(oit)), res_(res), cam_(frame_bounds(scene.bounds(), q.size)),
          inv_view_(glm::inverse(cam_.view)), sums_(pl_.position.size()), prev_alpha_(pl_.position.size(), -1.0f),
          cur_alpha_(pl_.position.size(), -1.0f) {
        pick_focus();
    }

    // The run: the graph without images, one warm-up frame, the lists kept for reading back.
    RenderOptions render_options() {
        RenderOptions opt;
        opt.graph_path = q_.graph_path;
        opt.sets = q_.sets;
        opt.size = q_.size;
        opt.time = q_.time ? *q_.time : default_quality_time(scene_);
        if (!q_.time) std::fprintf(stderr, "note: %s\n", picked_time_note(opt.time, scene_, "11 frames from the middle").c_str());
        opt.repeat = std::max(q_.repeat, 1);
        opt.write_images = false;
        opt.quiet = true;
        opt.warmup = 1;
        opt.keep = {oit_.heads, oit_.nodes, oit_.counter};
        opt.keep.insert(opt.keep.end(), oit_.oo_lists.begin(), oit_.oo_lists.end());
        opt.keep.insert(opt.keep.end(), oit_.oo_targets.begin(), oit_.oo_targets.end());
        for (double t : opt.time.times())
            for (int k = 0; k < opt.repeat; ++k) times_.push_back(t);
        return opt;
    }

    void frame(const Executor& ex, size_t frame) {
        const double t = times_[std::min(frame, times_.size() - 1)];
        if (frame == 0) res_.first_time = t;
        res_.last_time = t;
        // The graph's window and the resolve's K, as compiled.
        double window = 1.0;
        int keep = 32;
        for (const CompiledPass& p : ex.graph().passes) {
            if (p.name == oit_.fill && p.params.contains("window")) window = p.params["window"].get<double>();
            if (p.name == oit_.resolve && p.params.contains("max_fragments")) keep = p.params["max_fragments"].get<int>();
        }
        const bool whole = !(window > 0.0) || pl_.timeless;
        const FrameLists lists = read_lists(ex);
        sums_.clear();
        composite_pixels(lists, window_ranges(pl_, t - window, t, whole), keep);
        add_segment_measures(frame);
        ++res_.frames;
    }

    void summarize() {
        res_.focus_footprint = focus_fp_;
        res_.context_seen = context_seen_;
        res_.focus_visibility = focus_fp_ ? focus_ink_ / double(focus_fp_) : 0.0;
        res_.focus_unoccluded = focus_fp_ ? focus_unocc_ / double(focus_fp_) : 0.0;
        res_.focus_ink_share = all_ink_ > 0.0 ? focus_ink_ / all_ink_ : 0.0;
        res_.context_coverage = context_seen_ ? double(context_visible_) / double(context_seen_) : 0.0;
        res_.pixel_coverage = covered_ ? coverage_sum_ / double(covered_) : 0.0;
        if (changes_.empty()) return;
        double sum = 0.0;
        for (double d : changes_) sum += d;
        res_.alpha_change_mean = sum / double(changes_.size());
        const size_t i = std::min(changes_.size() - 1, size_t(0.95 * double(changes_.size())));
        std::nth_element(changes_.begin(), changes_.begin() + std::ptrdiff_t(i), changes_.end());
        res_.alpha_change_p95 = changes_[i];
        res_.alpha_change_max = *std::max_element(changes_.begin(), changes_.end());
    }

private:
    // Focus: the data segments whose mean speed is in the top focus_share, over the whole data.
    void pick_focus() {
        speed_.assign(pl_.position.size(), -1.0f);
        std::vector<float> all;
        for (const LineRange& r : pl_.lines)
            for (uint32_t k = r.first; k + 1 < r.first + r.count; ++k) {
                speed_[k] = 0.5f * (glm::length(pl_.velocity[k]) + glm::length(pl_.velocity[k + 1]));
                all.push_back(speed_[k]);
            }
        if (all.empty()) return;
        const size_t i = std::min(all.size() - 1, size_t((1.0 - q_.focus_share) * double(all.size())));
        std::nth_element(all.begin(), all.begin() + std::ptrdiff_t(i), all.end());
        res_.focus_speed = all[i];
    }
    bool is_focus(size_t s) const { return speed_[s] >= float(res_.focus_speed); }

    // The final lists, and the overflow of every list: fragments beyond the node buffer, and
    // opacity optimization's own lists (their overflow biases its opacities).
    FrameLists read_lists(const Executor& ex) {
        FrameLists l;
        const Texture heads_tex = ex.texture(oit_.heads);
        const Buffer nodes_buf = ex.buffer(oit_.nodes), counter_buf = ex.buffer(oit_.counter);
        const size_t capacity = nodes_buf.bytes / 16;
        const uint32_t count = read_buffer<uint32_t>(counter_buf, 1)[0];
        if (count > capacity) res_.overflow += count - capacity;
        l.nodes = read_buffer<glm::uvec4>(nodes_buf, std::min<size_t>(count, capacity));
        l.width = heads_tex.width, l.height = heads_tex.height;
        l.heads.resize(size_t(l.width) * size_t(l.height));
        glGetTextureImage(heads_tex.id, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(l.heads.size() * 4), l.heads.data());
        for (const std::string& name : oit_.oo_lists) {
            const std::vector<uint32_t> h = read_buffer<uint32_t>(ex.buffer(name), 8);
            if (h[6] > h[5]) res_.overflow += h[6] - h[5];
        }
        for (const std::string& name : oit_.oo_targets) res_.overflow += read_buffer<uint32_t>(ex.buffer(name), 8)[5];
        return l;
    }

    void composite_pixels(const FrameLists& l, const WindowRanges& wr, int keep) {
        for (int y = 0; y < l.height; ++y)
            for (int x = 0; x < l.width; ++x) {
                pixel_fragments(l, x, y, wr);
                if (frags_.empty()) continue;
                res_.fragments += frags_.size();
                if (frags_.size() > size_t(keep)) res_.overflow += frags_.size() - size_t(keep);
                coverage_sum_ += composite_pixel(frags_, keep, sums_);
                ++covered_;
            }
    }

    // The fragments of pixel (x, y), each placed on its line's nearest segment in the window.
    void pixel_fragments(const FrameLists& l, int x, int y, const WindowRanges& wr) {
        frags_.clear();
        const float span = cam_.far_plane - cam_.near_plane;
        size_t guard = 0;
        for (uint32_t i = l.heads[size_t(y) * size_t(l.width) + size_t(x)]; i != kEnd && i < l.nodes.size() && guard < l.nodes.size();
             i = l.nodes[i].z, ++guard) {
            const glm::uvec4 n = l.nodes[i];
            Fragment f;
            f.depth = bits_float(n.y);
            f.line = n.w;
            f.color = n.x;
            f.alpha = float(n.x >> 24) / 255.0f;
            // The fragment's point: its pixel centre at its linear depth (GL rows bottom-up).
            const float nx = (x + 0.5f) / float(l.width) * 2.0f - 1.0f;
            const float ny = (y + 0.5f) / float(l.height) * 2.0f - 1.0f;
            const float eye = cam_.near_plane + f.depth * span;
            const glm::vec3 p(inv_view_ * glm::vec4(nx * eye / cam_.proj[0][0], ny * eye / cam_.proj[1][1], -eye, 1.0f));
            f.segment = nearest_segment(pl_, wr, f.line, p);
            res_.located += f.segment >= 0;
            frags_.push_back(f);
        }
    }

    // The frame's per-segment measures and the change of each segment's mean opacity.
    void add_segment_measures(size_t frame) {
        double frame_max = 0.0;
        for (uint32_t s : sums_.seen) {
            const double a = sums_.footprint[s];
            all_ink_ += sums_.ink[s];
            if (is_focus(s)) {
                focus_ink_ += sums_.ink[s];
                focus_unocc_ += sums_.unoccluded[s];
                focus_fp_ += sums_.footprint[s];
            } else {
                ++context_seen_;
                context_visible_ += sums_.ink[s] / a >= q_.threshold;
            }
            cur_alpha_[s] = float(sums_.alpha[s] / a);
            if (prev_alpha_[s] >= 0.0f) {
                const double d = std::fabs(double(cur_alpha_[s]) - double(prev_alpha_[s]));
                changes_.push_back(d);
                frame_max = std::max(frame_max, d);
            }
        }
        if (frame > 0) res_.max_alpha_change_per_frame.push_back(frame_max);
        for (uint32_t s : prev_seen_) prev_alpha_[s] = -1.0f;
        prev_seen_ = sums_.seen;
        for (uint32_t s : prev_seen_) prev_alpha_[s] = cur_alpha_[s], cur_alpha_[s] = -1.0f;
    }

    const Scene& scene_;
    const Pathlines& pl_;
    const TransparencyOptions& q_;
    const Oit oit_;
    TransparencyResult& res_;
    const Camera cam_;
    const glm::mat4 inv_view_;
    std::vector<double> times_;  // per rendered frame
    std::vector<float> speed_;   // per segment (its first point), -1 for a line's last point
    SegmentSums sums_;
    std::vector<float> prev_alpha_, cur_alpha_;
    std::vector<uint32_t> prev_seen_;
    std::vector<double> changes_;
    std::vector<Fragment> frags_;
    double focus_ink_ = 0, focus_unocc_ = 0, all_ink_ = 0, coverage_sum_ = 0;
    size_t focus_fp_ = 0, context_seen_ = 0, context_visible_ = 0, covered_ = 0;
};

}  // namespace

void SegmentSums::clear() {
    for (uint32_t s : seen) ink[s] = unoccluded[s] = alpha[s] = 0.0, footprint[s] = 0;
    seen.clear();
}

double composite_pixel(std::vector<Fragment>& frags, int keep, SegmentSums& sums) {
    std::sort(frags.begin(), frags.end(), [](const Fragment& a, const Fragment& b) {
        return a.depth != b.depth ? a.depth < b.depth : (a.line != b.line ? a.line < b.line : a.color < b.color);
    });
    double alpha = 0.0;
    const size_t n = std::min(frags.size(), size_t(std::max(keep, 0)));
    for (size_t k = 0; k < n; ++k) {
        const Fragment& f = frags[k];
        const double transmittance = 1.0 - alpha;
        const double ink = alpha < kOpaque ? transmittance * f.alpha : 0.0;
        if (f.segment >= 0 && size_t(f.segment) < sums.footprint.size()) {
            const size_t s = size_t(f.segment);
            if (sums.footprint[s]++ == 0) sums.seen.push_back(uint32_t(s));
            sums.ink[s] += ink;
            sums.unoccluded[s] += transmittance;
            sums.alpha[s] += f.alpha;
        }
        alpha += ink;
    }
    return alpha;
}

void check_transparency_options(const TransparencyOptions& q) {
    if (q.time && q.time->times().size() * size_t(std::max(q.repeat, 1)) < 2)
        throw std::invalid_argument("time must give at least two frames (A:B:STEP), or repeat one");
    if (!(q.focus_share > 0.0 && q.focus_share < 1.0))
        throw std::invalid_argument("focus share must lie in (0, 1) (got " + std::to_string(q.focus_share) + ")");
    if (!(q.threshold > 0.0 && q.threshold <= 1.0))
        throw std::invalid_argument("the visibility threshold must lie in (0, 1] (got " + std::to_string(q.threshold) + ")");
}

TransparencyResult measure_transparency(Runtime& rt, const Scene& scene, const TransparencyOptions& q) {
    check_transparency_options(q);
    TransparencyResult res;
    const json full = expanded_graph_json(q.graph_path);
    res.graph = full.value("name", fs::path(q.graph_path).stem().string());
    Oit oit = find_oit(full);
    if (!oit.why_not.empty()) {
        res.not_measured = oit.why_not;
        return res;
    }
    Measurement m(scene, q, std::move(oit), res);
    render(rt, scene, m.render_options(), [&](const Executor& ex, size_t frame) { m.frame(ex, frame); });
    m.summarize();
    return res;
}

}  // namespace pathlet::quality
